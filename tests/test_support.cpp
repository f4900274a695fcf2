#include "tests/test_support.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/kernels/gaussian7_rows.hpp"

extern char** environ;

namespace aief::test {

std::string sample_path(const std::string& sequence, const std::string& file) {
  return std::string(AIEF_SAMPLE_DIR) + "/" + sequence + "/" + file;
}

cv::Mat load_sample_gray(const std::string& sequence, const std::string& file) {
  const std::string path = sample_path(sequence, file);
  cv::Mat image = cv::imread(path, cv::IMREAD_UNCHANGED);
  EXPECT_FALSE(image.empty()) << "missing sample " << path;
  if (image.channels() == 3) cv::cvtColor(image, image, cv::COLOR_BGR2GRAY);
  return image;
}

cv::Mat random_image(int width, int height, std::uint32_t seed) {
  cv::Mat image(height, width, CV_8UC1);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> value(0, 255);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      image.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(value(rng));
  return image;
}

cv::Mat random_textured_image(int width, int height, std::uint32_t seed) {
  cv::Mat noise = random_image(width, height, seed);
  cv::Mat smooth;
  cv::GaussianBlur(noise, smooth, cv::Size(5, 5), 1.5);
  cv::normalize(smooth, smooth, 0, 255, cv::NORM_MINMAX);
  return smooth;
}

std::string first_pixel_difference(const cv::Mat& a, const cv::Mat& b, int tolerance) {
  if (a.size() != b.size()) return "sizes differ";
  for (int y = 0; y < a.rows; ++y)
    for (int x = 0; x < a.cols; ++x) {
      const int va = a.at<std::uint8_t>(y, x), vb = b.at<std::uint8_t>(y, x);
      if (std::abs(va - vb) > tolerance) {
        std::ostringstream out;
        out << "first difference at (" << x << ", " << y << "): " << va << " vs " << vb;
        return out.str();
      }
    }
  return "";
}

cv::Mat gaussian7_ours(const cv::Mat& src) {
  cv::Mat dst(src.size(), CV_8UC1, cv::Scalar(0));
  gaussian7_rows_scalar(view_of(src), mutable_view_of(dst), 0, src.rows, 0, src.cols);
  return dst;
}

cv::Mat gaussian7_opencv(const cv::Mat& src) {
  cv::Mat dst;
  cv::GaussianBlur(src, dst, cv::Size(7, 7), 2, 2, cv::BORDER_REFLECT_101);
  return dst;
}

bool same_bytes(const Features& a, const Features& b) {
  if (a.keypoints.size() != b.keypoints.size() || a.descriptors != b.descriptors) return false;
  for (std::size_t i = 0; i < a.keypoints.size(); ++i)
    if (std::memcmp(&a.keypoints[i], &b.keypoints[i], sizeof(Keypoint)) != 0) return false;
  return true;
}

::testing::AssertionResult same_keypoint_at(const Features& features, std::size_t i,
                                            const std::vector<cv::KeyPoint>& keypoints,
                                            const cv::Mat& descriptors, std::size_t slot) {
  const Keypoint& want = features.keypoints[i];
  const cv::KeyPoint& got = keypoints[slot];
  if (!(got.pt.x == want.x && got.pt.y == want.y && got.size == want.size &&
        got.angle == want.angle_deg && got.response == want.response && got.octave == want.octave &&
        got.class_id == -1))
    return ::testing::AssertionFailure()
           << "engine keypoint " << i << " at slot " << slot << ": got (" << got.pt.x << ", "
           << got.pt.y << ") size " << got.size << " angle " << got.angle << " response "
           << got.response << " octave " << got.octave << " class_id " << got.class_id << ", want ("
           << want.x << ", " << want.y << ") size " << want.size << " angle " << want.angle_deg
           << " response " << want.response << " octave " << want.octave << " class_id -1";
  for (int b = 0; b < kDescriptorBytes; ++b)
    if (descriptors.at<std::uint8_t>(static_cast<int>(slot), b) !=
        features.descriptors[i][static_cast<std::size_t>(b)])
      return ::testing::AssertionFailure()
             << "engine keypoint " << i << " at slot " << slot << ", descriptor byte " << b << ": "
             << int{descriptors.at<std::uint8_t>(static_cast<int>(slot), b)} << " vs "
             << int{features.descriptors[i][static_cast<std::size_t>(b)]};
  return ::testing::AssertionSuccess();
}

::testing::AssertionResult same_features(const Features& features,
                                         const std::vector<cv::KeyPoint>& keypoints,
                                         const cv::Mat& descriptors) {
  if (keypoints.size() != features.keypoints.size())
    return ::testing::AssertionFailure()
           << keypoints.size() << " keypoints, want " << features.keypoints.size();
  if (descriptors.rows != static_cast<int>(features.descriptors.size()) ||
      descriptors.cols != kDescriptorBytes || descriptors.type() != CV_8U)
    return ::testing::AssertionFailure()
           << "descriptors " << descriptors.rows << " x " << descriptors.cols << " of type "
           << descriptors.type() << ", want " << features.descriptors.size() << " x "
           << kDescriptorBytes << " CV_8U";
  for (std::size_t i = 0; i < keypoints.size(); ++i)
    if (::testing::AssertionResult same = same_keypoint_at(features, i, keypoints, descriptors, i);
        !same)
      return same;
  return ::testing::AssertionSuccess();
}

namespace {

// PNG chunk checksum (ISO 3309 CRC-32).
std::uint32_t png_crc(const std::uint8_t* bytes, std::size_t count) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < count; ++i) {
    crc ^= bytes[i];
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

}  // namespace

std::vector<std::uint8_t> png_declaring(std::uint32_t width, std::uint32_t height) {
  std::vector<std::uint8_t> bytes;
  cv::imencode(".png", cv::Mat(64, 64, CV_8UC1, cv::Scalar(0)), bytes);
  for (int i = 0; i < 4; ++i) {  // IHDR's width and height, big-endian, at bytes 16 and 20
    bytes[16 + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(width >> (24 - 8 * i));
    bytes[20 + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(height >> (24 - 8 * i));
  }
  const std::uint32_t crc = png_crc(bytes.data() + 12, 17);  // over the chunk type and data
  for (int i = 0; i < 4; ++i)
    bytes[29 + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(crc >> (24 - 8 * i));
  return bytes;
}

TempFolder::TempFolder(const std::string& prefix) {
  std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "_XXXXXX")).string();
  if (::mkdtemp(pattern.data()) == nullptr)
    throw std::runtime_error("mkdtemp failed for " + pattern);
  path_ = pattern;
}

TempFolder::~TempFolder() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

CommandRun run_command(const std::string& program, const std::vector<std::string>& arguments) {
  const TempFolder scratch("aief_run");
  const std::string log = scratch.file("output.log");
  std::vector<std::string> words = {program};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = -1;
  const int spawned = posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  CommandRun run;
  if (spawned != 0) {
    run.output = "cannot start " + program;
    return run;
  }
  int status = 0;
  waitpid(pid, &status, 0);
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log, std::ios::binary);
  run.output.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return run;
}

CommandRun run_shell(const std::string& command_line) {
  CommandRun run;
  FILE* pipe = popen((command_line + " 2>&1").c_str(), "r");
  if (!pipe) return run;
  std::array<char, 512> buffer{};
  while (fgets(buffer.data(), static_cast<int>(buffer.size()), pipe)) run.output += buffer.data();
  const int status = pclose(pipe);
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

}  // namespace aief::test
