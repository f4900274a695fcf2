#pragma once
// The record of a pair group in matches.h5 (aief match --pairs): the matcher options it was
// matched with (their option record, core/options/matching_option_rows.cpp) and what it matched,
// each image's features as the features file records them (the group's option record and source,
// io/hdf5_file.hpp). A resumed run keeps a pair only when both are the same, and redoes it
// otherwise, as extract --batch redoes an image whose options or file changed: matches of
// re-extracted features, or of another matcher, are never kept.
//
// Stored as the pair group's string attributes matcher, options0, options1, source0 and source1
// ("" where the features file records nothing; source as "BYTES MTIME_NS"): PairRecord's field
// list below.
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "aief/match.hpp"
#include "io/record_fields.hpp"

namespace aief::io {

class Hdf5File;

struct PairRecord {
  std::string matcher;             // the matcher's option record, JSON text
  std::string options0, options1;  // each image's features' option record, JSON text, or ""
  std::string source0, source1;    // each image's source record, "BYTES MTIME_NS", or ""
};

// The attributes of a pair group, in the order they are written.
template <>
struct RecordFields<PairRecord> {
  using R = PairRecord;
  static constexpr auto list = std::tuple{AIEF_RECORD_FIELD(matcher), AIEF_RECORD_FIELD(options0),
                                          AIEF_RECORD_FIELD(options1), AIEF_RECORD_FIELD(source0),
                                          AIEF_RECORD_FIELD(source1)};
};

// Not defaulted: installed headers stay C++17 (tests/consumer builds with it).
inline bool operator==(const PairRecord& a, const PairRecord& b) { return same_fields(a, b); }
inline bool operator!=(const PairRecord& a, const PairRecord& b) { return !(a == b); }

// What a recorded pair group does not share with this run's record `now`, for a message: the
// matcher options that change the matches ("kind mutual -> ratio"), the image whose features
// changed ("the features of 'a.png': n_features 500 -> 1000", "the image of 'a.png' changed");
// for a group without a record (an older aief's, or another tool's), kNoPairRecord. Empty: the
// group holds what this run would write.
inline constexpr std::string_view kNoPairRecord =
    "no record of its matcher and features (an older aief's or another tool's matches)";
std::vector<std::string> pair_changes(const std::optional<PairRecord>& recorded,
                                      const PairRecord& now, const std::string& name0,
                                      const std::string& name1);

// The records of this run's pairs: the matcher's, and each image's features' as `features`
// records them, read once per image (records that are the same text are kept once).
class PairRecords {
 public:
  PairRecords(const Hdf5File& features, const MatchOptions& matcher);
  PairRecord of(const std::string& name0, const std::string& name1);

 private:
  struct Identity {
    const std::string* options;
    std::string source;
  };
  const Identity& identity(const std::string& name);

  const Hdf5File& features_;
  std::string matcher_;
  std::unordered_set<std::string> options_texts_;
  std::unordered_map<std::string, Identity> identities_;
};

}  // namespace aief::io
