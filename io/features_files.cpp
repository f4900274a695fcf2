#include "io/features_files.hpp"

#include <filesystem>
#include <sstream>

#include <opencv2/core.hpp>

#include "aief/error.hpp"
#include "io/json_writer.hpp"
#include "io/npz_writer.hpp"

namespace aief::io {

namespace {

void write_options(JsonWriter& json, const ExtractorOptions& o) {
  json.key("options").begin_object();
  json.field("n_features", o.n_features).field("scale_factor", o.scale_factor).field("n_levels", o.n_levels);
  json.field("fast_threshold", o.fast_threshold).field("fast_min_threshold", o.fast_min_threshold);
  json.field("block_size", o.block_size).field("distribution", to_string(o.distribution));
  json.field("entropy", to_string(o.entropy)).field("entropy_threshold", o.entropy_threshold);
  json.field("auto_threshold", o.auto_threshold).field("kernels", to_string(o.kernels)).field("threads", o.threads);
  json.end_object();
}

void write_info(JsonWriter& json, const ExtractionInfo& info) {
  json.key("info").begin_object();
  json.field("entropy_threshold_requested", info.entropy_threshold_requested);
  json.field("entropy_threshold_used", info.entropy_threshold_used);
  json.field("threshold_lowered", info.threshold_lowered);
  json.field("image_entropy_bits", info.image_entropy_bits);
  json.field("blocks_total", info.blocks_total).field("blocks_kept", info.blocks_kept);
  json.end_object();
}

std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

std::string features_json(const std::string& image_path, const Features& features, const ExtractorOptions& options) {
  std::ostringstream out;
  JsonWriter json(out);
  json.begin_object();
  json.field("image", image_path).field("width", features.image_width).field("height", features.image_height);
  write_options(json, options);
  write_info(json, features.info);
  json.key("keypoints").begin_array();
  for (const Keypoint& kp : features.keypoints) {
    json.begin_object();
    json.field("x", kp.x).field("y", kp.y).field("size", kp.size).field("angle", kp.angle_deg);
    json.field("response", kp.response).field("octave", kp.octave);
    json.end_object();
  }
  json.end_array();
  json.key("descriptors_hex").begin_array();
  for (const Descriptor& d : features.descriptors) json.value(hex_of(d.data(), d.size()));
  json.end_array();
  json.end_object();
  return out.str();
}

void write_features_json(const std::string& path, const std::string& image_path, const Features& features,
                         const ExtractorOptions& options) {
  write_file_atomically(path, features_json(image_path, features, options));
}

void write_features_yaml(const std::string& path, const std::string& image_path, const Features& features) {
  std::vector<cv::KeyPoint> keypoints;
  keypoints.reserve(features.keypoints.size());
  for (const Keypoint& kp : features.keypoints)
    keypoints.emplace_back(cv::Point2f(kp.x, kp.y), kp.size, kp.angle_deg, kp.response, kp.octave, -1);
  cv::Mat descriptors(static_cast<int>(features.descriptors.size()), kDescriptorBytes, CV_8U);
  for (int r = 0; r < descriptors.rows; ++r)
    std::copy(features.descriptors[static_cast<std::size_t>(r)].begin(), features.descriptors[static_cast<std::size_t>(r)].end(),
              descriptors.ptr<std::uint8_t>(r));
  // FileStorage picks the format from the name: keep the .yml extension on the temporary file.
  const std::filesystem::path final_path(path);
  const std::string temporary = (final_path.parent_path() / (".tmp." + final_path.filename().string())).string();
  try {
    cv::FileStorage fs(temporary, cv::FileStorage::WRITE);
    if (!fs.isOpened()) throw Error("cannot write '" + path + "'");
    fs << "image" << image_path << "width" << features.image_width << "height" << features.image_height;
    cv::write(fs, "keypoints", keypoints);
    fs << "descriptors" << descriptors;
    fs.release();
  } catch (const cv::Exception& e) {
    throw Error("cannot write '" + path + "': " + e.what());
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) throw Error("cannot write '" + path + "': " + ec.message());
}

void write_features(const std::string& path, const std::string& image_path, const Features& features,
                    const ExtractorOptions& options) {
  const std::string ext = extension_of(path);
  if (ext == ".json") return write_features_json(path, image_path, features, options);
  if (ext == ".yml" || ext == ".yaml") return write_features_yaml(path, image_path, features);
  if (ext == ".npz") return write_features_npz(path, features);
  throw Error("output '" + path + "' must end in .json, .yml, .yaml or .npz");
}

}  // namespace aief::io
