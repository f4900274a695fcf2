#pragma once
// Shared by the tests: seeded random images and the bundled sample images.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "aief/cv_image_view.hpp"  // view_of, for every test
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
