#pragma once
// The option record of an output file: every field of the effective ExtractorOptions (the mode's
// values included), from the option table (core/options/option_table.hpp). JSON files hold it as
// their "options" object; YAML, npz and HDF5 as the compact JSON text option_record_json writes
// (YAML: the string "options"; npz: the bytes member "options"; HDF5: each image group's string
// attribute "options"). Batch resume and merge compare records with option_changes, through
// the option table (only the fields that change the output count).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "aief/match.hpp"
#include "aief/options.hpp"
#include "io/json_writer.hpp"

namespace aief::io {

// The record as the JSON object {"n_features":1000,"scale_factor":1.2,...}: the one writer of it.
void write_option_record(JsonWriter& json, const ExtractorOptions& options);

// The same on one line, with no space: what YAML, npz and HDF5 hold.
std::string option_record_json(const ExtractorOptions& options);

// What an output whose record is `recorded` (its JSON text) does not share with a run of
// `options`: each field that changes the output and differs ("n_features 500 -> 3000", the
// recorded value first), or, for an output without a readable record (an aief before records),
// kNoOptionRecord: such an output is redone, since nothing says how it was made. Empty: the run
// would write the same bytes.
inline constexpr std::string_view kNoOptionRecord = "no option record (an older aief's output)";
std::vector<std::string> option_changes(const std::optional<std::string>& recorded,
                                        const ExtractorOptions& options);

// The same between two records: what `other` does not share with `first` ("n_features 500 ->
// 1000", first's value first); an unreadable record is kNoOptionRecord.
std::vector<std::string> option_changes(const std::string& first, const std::string& other);

// The same for the matcher options a matches file records (io/match_record.hpp): the record
// {"kind":"mutual","ratio":0.8,"max_distance":256}, and what `other` does not share with `first`
// ("kind mutual -> ratio"; kNoOptionRecord for an unreadable record).
std::string match_option_record_json(const MatchOptions& options);
std::vector<std::string> match_option_changes(const std::string& first, const std::string& other);

// The descriptor an output holds, from its option record (JSON text): the record's "descriptor",
// or rbrief for a record without one or no record (an aief from before the box descriptor, which
// wrote rBRIEF only). Throws aief::Error for a name it does not know.
DescriptorKind recorded_descriptor(const std::optional<std::string>& recorded);

// "n_features 500 -> 3000, entropy histogram -> off": changes as messages list them.
std::string listed(const std::vector<std::string>& changes);

}  // namespace aief::io
