// The names of the option enums (one table per enum: core/options/option_names.hpp). validate() and
// options_for_mode() are made from the option table (core/options/extractor_option_rows.cpp).
#include "aief/options.hpp"

#include "core/options/option_names.hpp"
#include "core/options/option_table.hpp"

namespace aief {

std::string_view to_string(Distribution value) { return option_names::name_of(value); }
std::string_view to_string(EntropyMeasure value) { return option_names::name_of(value); }
std::string_view to_string(KernelSet value) { return option_names::name_of(value); }
std::string_view to_string(Mode value) { return option_names::name_of(value); }
std::string_view to_string(CoordinateMap value) { return option_names::name_of(value); }
std::string_view to_string(StarvationGuard value) { return option_names::name_of(value); }
std::string_view to_string(CandidateRanking value) { return option_names::name_of(value); }
std::string_view to_string(MatcherKind value) { return option_names::name_of(value); }
std::string_view to_string(PyramidResampling value) { return option_names::name_of(value); }
std::string_view to_string(DetectionCells value) { return option_names::name_of(value); }
std::string_view to_string(QuadtreeTies value) { return option_names::name_of(value); }
std::string_view to_string(Orientation value) { return option_names::name_of(value); }
std::string_view to_string(QuadtreeWeight value) { return option_names::name_of(value); }
std::string_view to_string(FastThresholdFrom value) { return option_names::name_of(value); }
std::string_view to_string(DescriptorKind value) { return option_names::name_of(value); }
std::string_view to_string(ScaleSelection value) { return option_names::name_of(value); }

Distribution parse_distribution(std::string_view name) {
  return option_names::parse<Distribution>(name);
}
EntropyMeasure parse_entropy_measure(std::string_view name) {
  return option_names::parse<EntropyMeasure>(name);
}
KernelSet parse_kernel_set(std::string_view name) { return option_names::parse<KernelSet>(name); }
Mode parse_mode(std::string_view name) { return option_names::parse<Mode>(name); }
CoordinateMap parse_coordinate_map(std::string_view name) {
  return option_names::parse<CoordinateMap>(name);
}
StarvationGuard parse_starvation_guard(std::string_view name) {
  return option_names::parse<StarvationGuard>(name);
}
DescriptorKind parse_descriptor_kind(std::string_view name) {
  return option_names::parse<DescriptorKind>(name);
}
CandidateRanking parse_candidate_ranking(std::string_view name) {
  return option_names::parse<CandidateRanking>(name);
}

MatcherKind parse_matcher_kind(std::string_view name) {
  return option_names::parse<MatcherKind>(name);
}

double parse_candidate_pool(std::string_view text) {
  ExtractorOptions options;
  const option_table::OptionRow& pool = option_table::row("candidate_pool");
  pool.field.set(options, option_table::parse_value(pool, text, "candidate pool"));
  return options.candidate_pool;
}

}  // namespace aief
