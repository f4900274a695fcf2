#pragma once
// Shared by the tests: seeded random images and the bundled sample images, comparisons of
// images and features, temporary folders, running the built tool.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "aief/cv_image_view.hpp"  // view_of, for every test
#include "aief/features.hpp"
#include "aief/image.hpp"

namespace aief::test {

// Path of a bundled sample, e.g. sample_path("graf", "img1.png").
std::string sample_path(const std::string& sequence, const std::string& file);

// The bundled sample as 8-bit gray (OpenCV's cvtColor BGR2GRAY); fails the test if missing.
cv::Mat load_sample_gray(const std::string& sequence, const std::string& file);

// Uniform random u8 image, reproducible from the seed.
cv::Mat random_image(int width, int height, std::uint32_t seed);

// Random image smoothed and contrast-stretched so it has corners of every strength.
cv::Mat random_textured_image(int width, int height, std::uint32_t seed);

// A valid small PNG file whose header (checksum fixed) declares width x height: a decompression
// bomb's header, to test that the size is refused before decoding.
std::vector<std::uint8_t> png_declaring(std::uint32_t width, std::uint32_t height);

// The first pixel where two 8-bit images differ by more than `tolerance`, or "" when none does.
std::string first_pixel_difference(const cv::Mat& a, const cv::Mat& b, int tolerance);

// The engine's 7x7 Gaussian of a whole image (its scalar reference,
// core/kernels/gaussian7_rows.hpp), and cv::GaussianBlur's with the same kernel and border.
cv::Mat gaussian7_ours(const cv::Mat& src);
cv::Mat gaussian7_opencv(const cv::Mat& src);

// Every keypoint byte and descriptor byte equal.
bool same_bytes(const Features& a, const Features& b);

// Engine keypoint `i` of `features` and its descriptor stand at position `slot` of an OpenCV
// output (cv::KeyPoint field for field, class_id -1; the descriptor row byte for byte).
::testing::AssertionResult same_keypoint_at(const Features& features, std::size_t i,
                                            const std::vector<cv::KeyPoint>& keypoints,
                                            const cv::Mat& descriptors, std::size_t slot);
// An OpenCV output is exactly `features`, in the engine's order: counts, a CV_8U descriptor
// matrix of 32 columns, then every keypoint; the first difference is reported.
::testing::AssertionResult same_features(const Features& features,
                                         const std::vector<cv::KeyPoint>& keypoints,
                                         const cv::Mat& descriptors);

// A fresh folder of its own under the system temporary folder (mkdtemp), removed with all it
// holds when the object goes: two suites running at once never share a path.
class TempFolder {
 public:
  explicit TempFolder(const std::string& prefix = "aief_test");
  ~TempFolder();
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

// A command line tool run to its end: its exit status (-1 when it did not exit) and what it wrote
// to stdout and stderr, interleaved.
struct CommandRun {
  int status = -1;
  std::string output;
};
// Runs `program` with `arguments` (no shell: any name passes as it is). CLI tests pass the built
// tool, AIEF_CLI_PATH.
CommandRun run_command(const std::string& program, const std::vector<std::string>& arguments);
// Runs `command_line` through sh, stderr joined to stdout (for tests that need the shell's
// quoting, redirections or `timeout`).
CommandRun run_shell(const std::string& command_line);

}  // namespace aief::test
