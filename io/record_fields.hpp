#pragma once
// One field list per result record: the record's fields, in the order every output writes them,
// each with the key it has in every output (JSON and YAML files, the Python dicts, aief eval's
// JSON, the type stub's TypedDicts). A writer walks the list (for_each_field) instead of naming
// the fields; a field added to the struct and not to its list fails the record tests
// (tests/test_record_fields.cpp counts the struct's fields), and python/tests/test_stub.py holds
// the stub's TypedDicts to the lists.
//
// A record's list is a specialisation of RecordFields<Record> holding `list`, a tuple of
// field("key", &Record::member), AIEF_RECORD_FIELD(member) where the key is the member's name; the
// lists of the engine's records are below, aief eval's rows' beside PairResult
// (tools/eval/methods.hpp).
#include <cstddef>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <vector>

#include "aief/adapt.hpp"
#include "aief/features.hpp"
#include "aief/match.hpp"

namespace aief::io {

template <class Record, class T>
struct RecordField {
  std::string_view key;
  T Record::*member;
};

template <class Record, class T>
constexpr RecordField<Record, T> field(std::string_view key, T Record::*member) {
  return {key, member};
}

template <class Record>
struct RecordFields;  // specialised per record: static constexpr auto list = std::tuple{...};

// field("member", &R::member) in a specialisation whose `R` is the record: a field whose key is
// its member's name (every field so far), the name written once.
#define AIEF_RECORD_FIELD(member) ::aief::io::field(#member, &R::member)

// visit(key, value) for each field of `record`, in the list's order (value const if record is).
template <class Record, class Visit>
void for_each_field(Record& record, Visit&& visit) {
  std::apply([&](const auto&... f) { (visit(f.key, record.*(f.member)), ...); },
             RecordFields<std::remove_const_t<Record>>::list);
}

// The keys of a record's list, in order.
template <class Record>
std::vector<std::string_view> field_keys() {
  std::vector<std::string_view> keys;
  std::apply([&](const auto&... f) { (keys.push_back(f.key), ...); }, RecordFields<Record>::list);
  return keys;
}

// Whether two records hold the same value in every field of the list.
template <class Record>
bool same_fields(const Record& a, const Record& b) {
  return std::apply([&](const auto&... f) { return ((a.*(f.member) == b.*(f.member)) && ...); },
                    RecordFields<Record>::list);
}

// The number of fields in a record's list (tests compare it with the struct's).
template <class Record>
constexpr std::size_t field_list_size() {
  return std::tuple_size_v<std::remove_const_t<decltype(RecordFields<Record>::list)>>;
}

// How the entropy mask went on one image: Features::info.
template <>
struct RecordFields<ExtractionInfo> {
  using R = ExtractionInfo;
  static constexpr auto list = std::tuple{AIEF_RECORD_FIELD(entropy_threshold_requested),
                                          AIEF_RECORD_FIELD(entropy_threshold_used),
                                          AIEF_RECORD_FIELD(threshold_lowered),
                                          AIEF_RECORD_FIELD(image_entropy_bits),
                                          AIEF_RECORD_FIELD(blocks_total),
                                          AIEF_RECORD_FIELD(blocks_kept),
                                          AIEF_RECORD_FIELD(auto_threshold_effectiveness)};
};

// One threshold of the adaptive sweep: AdaptResult::curve.
template <>
struct RecordFields<SweepPoint> {
  using R = SweepPoint;
  static constexpr auto list =
      std::tuple{AIEF_RECORD_FIELD(threshold),     AIEF_RECORD_FIELD(kept_blocks),
                 AIEF_RECORD_FIELD(kept_blocks_b), AIEF_RECORD_FIELD(keypoints_a),
                 AIEF_RECORD_FIELD(keypoints_b),   AIEF_RECORD_FIELD(putative),
                 AIEF_RECORD_FIELD(inliers),       AIEF_RECORD_FIELD(cmr),
                 AIEF_RECORD_FIELD(eligible)};
};

// One putative match: aief match's JSON rows, the columns of Python's match arrays (M x 3).
template <>
struct RecordFields<Match> {
  using R = Match;
  static constexpr auto list =
      std::tuple{AIEF_RECORD_FIELD(query), AIEF_RECORD_FIELD(train), AIEF_RECORD_FIELD(distance)};
};

}  // namespace aief::io
