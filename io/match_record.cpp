#include "io/match_record.hpp"

#include "io/hdf5_file.hpp"
#include "io/option_record.hpp"

namespace aief::io {

namespace {

// The changes of one image's features between two records.
void add_feature_changes(const std::string& name, const std::string& options_before,
                         const std::string& options_now, const std::string& source_before,
                         const std::string& source_now, std::vector<std::string>& changes) {
  if (options_before != options_now) {
    const std::vector<std::string> differ =
        options_before.empty() || options_now.empty()
            ? std::vector<std::string>{options_before.empty() ? "no option record before"
                                                              : "no option record now"}
            : option_changes(options_before, options_now);
    if (!differ.empty()) changes.push_back("the features of '" + name + "': " + listed(differ));
  }
  if (source_before != source_now) changes.push_back("the image of '" + name + "' changed");
}

}  // namespace

std::vector<std::string> pair_changes(const std::optional<PairRecord>& recorded,
                                      const PairRecord& now, const std::string& name0,
                                      const std::string& name1) {
  if (!recorded) return {std::string(kNoPairRecord)};
  std::vector<std::string> changes = match_option_changes(recorded->matcher, now.matcher);
  add_feature_changes(name0, recorded->options0, now.options0, recorded->source0, now.source0,
                      changes);
  add_feature_changes(name1, recorded->options1, now.options1, recorded->source1, now.source1,
                      changes);
  return changes;
}

PairRecords::PairRecords(const Hdf5File& features, const MatchOptions& matcher)
    : features_(features), matcher_(match_option_record_json(matcher)) {}

const PairRecords::Identity& PairRecords::identity(const std::string& name) {
  if (const auto found = identities_.find(name); found != identities_.end()) return found->second;
  const std::string& options =
      *options_texts_.insert(features_.option_record(name).value_or("")).first;
  std::string source;
  if (const std::optional<SourceRecord> recorded = features_.recorded_source(name))
    source = std::to_string(recorded->bytes) + " " + std::to_string(recorded->mtime_ns);
  return identities_.emplace(name, Identity{&options, std::move(source)}).first->second;
}

PairRecord PairRecords::of(const std::string& name0, const std::string& name1) {
  const Identity &image0 = identity(name0), &image1 = identity(name1);
  return {matcher_, *image0.options, *image1.options, image0.source, image1.source};
}

}  // namespace aief::io
