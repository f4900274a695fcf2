#pragma once
// The option record of an output file: every field of the effective ExtractorOptions, from the
// option table (core/option_table.hpp). JSON files hold it as their "options" object, YAML as an
// "options" map, npz as an "options" member and HDF5 as each image group's "options" attribute,
// the last two as this compact JSON text. Batch resume and merge compare records with
// option_table::output_differences.
#include <optional>
#include <string>
#include <string_view>

#include "aief/options.hpp"
#include "core/option_table.hpp"

namespace aief::io {

// {"n_features":1000,"scale_factor":1.2,...}: one line, the JSON file's numbers and names.
std::string option_record_json(const ExtractorOptions& options);

// The fields of a flat JSON object of scalars (what option_record_json writes), values as
// written with strings unquoted; nullopt when `text` is not one.
std::optional<option_table::RecordedOptions> read_option_record_json(std::string_view text);

}  // namespace aief::io
