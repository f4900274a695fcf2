#include "tests/test_support.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

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
