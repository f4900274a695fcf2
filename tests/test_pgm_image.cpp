// The OpenCV-free PGM reader of the tests (tests/pgm_image.hpp): the bundled sample, a round
// trip, and every malformed header refused with aief::Error, never a crash.
#include <gtest/gtest.h>

#include "aief/error.hpp"
#include "tests/pgm_image.hpp"

namespace aief::test {
namespace {

TEST(PgmImage, ReadsTheBundledSample) {
  const GrayImage image = read_pgm(std::string(AIEF_SAMPLE_DIR) + "/graf/img1_center_320x240.pgm");
  EXPECT_EQ(image.width(), 320);
  EXPECT_EQ(image.height(), 240);
  long long sum = 0;
  for (int i = 0; i < 320 * 240; ++i) sum += image.data()[i];
  EXPECT_GT(sum, 320LL * 240 * 20);  // a real photo, not zeros
}

TEST(PgmImage, RoundTripsAndSkipsComments) {
  GrayImage image(5, 3);
  for (int i = 0; i < 15; ++i) image.data()[i] = static_cast<std::uint8_t>(i * 17);
  const std::string bytes = format_pgm(image);
  const GrayImage back = parse_pgm(bytes);
  ASSERT_EQ(back.width(), 5);
  ASSERT_EQ(back.height(), 3);
  EXPECT_TRUE(std::equal(image.data(), image.data() + 15, back.data()));
  const GrayImage commented =
      parse_pgm("P5\n# a comment\n5 3 # another\n255\n" + bytes.substr(bytes.size() - 15));
  EXPECT_TRUE(std::equal(image.data(), image.data() + 15, commented.data()));
}

TEST(PgmImage, MalformedFilesAreRefusedWithAMessage) {
  const std::string pixels(6, '\x7f');
  for (const std::string& bytes :
       {std::string(""), std::string("P2\n3 2\n255\n") + pixels,
        std::string("P5\n3 2\n65535\n") + pixels, std::string("P5\n3 2\n255\n") + pixels.substr(1),
        std::string("P5\n0 2\n255\n"), std::string("P5\n3\n"),
        std::string("P5\n99999999999 2\n255\n"), std::string("P5 3 2 255")}) {
    EXPECT_THROW(parse_pgm(bytes), Error) << "input: " << bytes;
  }
  EXPECT_THROW(read_pgm(std::string(AIEF_SAMPLE_DIR) + "/no_such_file.pgm"), Error);
}

}  // namespace
}  // namespace aief::test
