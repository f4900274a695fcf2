// Every result record has one field list (io/record_fields.hpp) and it has every field of the
// struct: a field added to ExtractionInfo, SweepPoint, Match or PairRecord without its entry fails
// here. The writers walk the lists: the JSON of an image's features holds the info fields in the
// list's order, and two pair records differ when any listed field does.
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "io/features_files.hpp"
#include "io/match_record.hpp"
#include "io/record_fields.hpp"
#include "tests/field_count.hpp"

namespace aief::io {
namespace {

using test::field_count;

TEST(RecordFields, EachListHasEveryFieldOfItsRecord) {
  EXPECT_EQ(field_list_size<ExtractionInfo>(), field_count<ExtractionInfo>());
  EXPECT_EQ(field_list_size<SweepPoint>(), field_count<SweepPoint>());
  EXPECT_EQ(field_list_size<Match>(), field_count<Match>());
  EXPECT_EQ(field_list_size<PairRecord>(), field_count<PairRecord>());
}

TEST(RecordFields, KeysAreDistinctSnakeCaseWords) {
  const auto check = [](const std::vector<std::string_view>& keys) {
    for (std::size_t i = 0; i < keys.size(); ++i) {
      EXPECT_FALSE(keys[i].empty());
      EXPECT_EQ(keys[i].find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_"),
                std::string_view::npos)
          << keys[i];
      for (std::size_t j = 0; j < i; ++j) EXPECT_NE(keys[i], keys[j]);
    }
  };
  check(field_keys<ExtractionInfo>());
  check(field_keys<SweepPoint>());
  check(field_keys<Match>());
  check(field_keys<PairRecord>());
}

TEST(RecordFields, TheFeaturesJsonHoldsTheInfoFieldsInTheListsOrder) {
  Features features;
  features.info.blocks_total = 12;
  features.info.blocks_kept = 7;
  const std::string json = features_json("a.png", features, ExtractorOptions{}, std::nullopt);
  std::size_t at = json.find("\"info\":");
  ASSERT_NE(at, std::string::npos) << json;
  for (std::string_view key : field_keys<ExtractionInfo>()) {
    const std::size_t next = json.find("\"" + std::string(key) + "\":", at);
    ASSERT_NE(next, std::string::npos) << key << " is not in its place in\n" << json;
    at = next;
  }
  EXPECT_NE(json.find("\"blocks_kept\":7"), std::string::npos) << json;
}

TEST(RecordFields, PairRecordsDifferWhenAnyListedFieldDoes) {
  const PairRecord base{"m", "o0", "o1", "s0", "s1"};
  EXPECT_TRUE(base == base);
  for (std::size_t changed = 0; changed < field_list_size<PairRecord>(); ++changed) {
    PairRecord other = base;
    std::size_t index = 0;
    for_each_field(other, [&](std::string_view, std::string& value) {
      if (index++ == changed) value += "x";
    });
    EXPECT_FALSE(other == base) << "field " << changed;
  }
}

}  // namespace
}  // namespace aief::io
