#include "bench/bench_support.hpp"

#include <cstdlib>
#include <map>
#include <sstream>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace aief::bench {

const cv::Mat& sample_gray(const std::string& sequence) {
  static std::map<std::string, cv::Mat> cache;
  auto it = cache.find(sequence);
  if (it != cache.end()) return it->second;
  const std::string path = std::string(AIEF_SAMPLE_DIR) + "/" + sequence + "/img1.png";
  cv::Mat image = cv::imread(path, cv::IMREAD_GRAYSCALE);
  if (image.empty()) throw std::runtime_error("benchmark sample missing: " + path);
  return cache.emplace(sequence, image).first->second;
}

const std::vector<NamedImage>& benchmark_images() {
  static const std::vector<NamedImage> images = [] {
    std::vector<NamedImage> list;
    const auto resized = [](const cv::Mat& source, int w, int h) {
      cv::Mat out;
      cv::resize(source, out, cv::Size(w, h), 0, 0, cv::INTER_AREA);
      return out;
    };
    list.push_back({"640x480", resized(sample_gray("graf"), 640, 480)});
    list.push_back({"graf_800x640", sample_gray("graf")});
    list.push_back({"leuven_900x600", sample_gray("leuven")});
    list.push_back({"boat_850x680", sample_gray("boat")});
    list.push_back({"1920x1080", resized(sample_gray("boat"), 1920, 1080)});
    // Frames of your own (a rendered 640x480 or 752x480 frame of scripts/make_sequences.py):
    // AIEF_BENCH_FRAMES=PATH[,PATH...], each named by its file name and size.
    if (const char* frames = std::getenv(kBenchFramesVariable)) {
      std::stringstream paths(frames);
      for (std::string path; std::getline(paths, path, ',');) {
        if (path.empty()) continue;
        cv::Mat image = cv::imread(path, cv::IMREAD_GRAYSCALE);
        if (image.empty())
          throw std::runtime_error(std::string(kBenchFramesVariable) + ": cannot read " + path);
        const std::string file = path.substr(path.find_last_of('/') + 1);
        list.push_back({file.substr(0, file.find('.')) + "_" + std::to_string(image.cols) + "x" +
                            std::to_string(image.rows),
                        image});
      }
    }
    return list;
  }();
  return images;
}

}  // namespace aief::bench
