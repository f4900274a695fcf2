#pragma once
// When an extractor option acts: the rows' acts_with conditions and read_by_sweep
// (core/options/option_table.hpp), the one rule the front ends (through resolve_options) and
// ExtractorOptions::validate() read. An option that cannot act with the others does nothing;
// accepting it would let a user believe it changed the output (--mode faithful
// --fast-threshold-from entropy gave faithful's bytes).
//
// Two halves, because a mode sets values the user did not ask for:
//   - resolve_options refuses a *given* option that cannot act when it changes a value (the
//     value the mode sets, or the value of a mode whose every value is given, is no request);
//   - validate() refuses, in any options however made (C++, Feature2D, a pickle), a variant (a
//     choice or a switch) that cannot act which neither ExtractorOptions{} nor any mode holds
//     (fast_threshold_from entropy with ORB-SLAM's cells); numbers, carried along in a struct,
//     only when given.
#include <string>
#include <vector>

#include "core/options/option_table.hpp"

namespace aief::option_table {

// The first of row.acts_with's conditions that `options` does not meet.
struct UnmetCondition {
  const OptionRow* row = nullptr;  // the field that stops it; null: the row acts
  std::string needed, holds;       // the value it needs and the value it holds, as text
};
UnmetCondition unmet_condition(const OptionRow& row, const ExtractorOptions& options);

// validate()'s half (see above).
void check_fields_act(const ExtractorOptions& options);

// The modes other than `mode` whose every value is among `given` (as Extractor.options of such a
// mode's extractor gives them): a value they set is no request either.
std::vector<Mode> modes_given_whole(const std::vector<GivenOption>& given);

// resolve_options' half: `changed` are the given options that changed a value of `options` (the
// resolved options); `reference` the modes whose values are no request; `mode_named` and `mode`
// name the mode in the messages. Throws aief::Error naming the option, what it needs and what
// stops it.
void refuse_given_that_cannot_act(const std::vector<const GivenOption*>& changed,
                                  const std::vector<GivenOption>& given,
                                  const ExtractorOptions& options,
                                  const std::vector<Mode>& reference, const std::string& mode_named,
                                  Mode mode, Use use);

}  // namespace aief::option_table
