#include "io/features_files.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <variant>

#include <opencv2/core.hpp>

#include "aief/error.hpp"
#include "io/json_writer.hpp"
#include "io/option_record.hpp"
#include "io/record_fields.hpp"
#include "io/temporary_files.hpp"

namespace aief::io {

namespace {

void write_info(JsonWriter& json, const ExtractionInfo& info,
                const std::vector<std::string>* decoder_warnings) {
  json.key("info").begin_object();
  for_each_field(info, [&](std::string_view key, const auto& value) { json.field(key, value); });
  if (decoder_warnings) {
    json.key("decoder_warnings").begin_array();
    for (const std::string& warning : *decoder_warnings) json.value(warning);
    json.end_array();
  }
  json.end_object();
}

void write_source(JsonWriter& json, const SourceRecord& source) {
  json.key("source").begin_object();
  json.field("name", source.name)
      .field("bytes", static_cast<long long>(source.bytes))
      .field("mtime_ns", source.mtime_ns);
  json.end_object();
}

// The exact text write_source gives inside a result's top-level object: what a JSON result of
// this source contains (the writer's layout depends only on the depth, the same here).
std::string source_json_fragment(const SourceRecord& source) {
  std::ostringstream out;
  JsonWriter json(out);
  json.begin_object();
  write_source(json, source);
  json.end_object();
  const std::string text = out.str();  // "{" fragment "\n}\n"
  return text.substr(1, text.size() - 4);
}

std::string read_bytes(const std::string& path, std::ios::off_type from_end, std::size_t count) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  if (from_end > 0) {
    in.seekg(0, std::ios::end);
    if (in.tellg() < from_end) return {};
    in.seekg(-from_end, std::ios::end);
  }
  std::string text(count, '\0');
  in.read(text.data(), static_cast<std::streamsize>(count));
  text.resize(static_cast<std::size_t>(in.gcount()));
  return text;
}

// A string value for OpenCV's YAML writer, quoted and escaped here. The writer takes a string
// beginning with '{' or '[' for the start of a map or a list (`image: !!b}.png`) and leaves one
// that begins and ends with the same quote unquoted (its reader then strips them); a string it is
// given already in double quotes is written as it is. Its reader (4.6) decodes \\ \" \n \r \t but
// not \x escapes, and holds at most 4095 bytes a string: a name with another control character,
// or longer, is refused here rather than written in a form that reads back as another name.
std::string yaml_quoted(const std::string& value, const char* key) {
  constexpr std::size_t kLongestString = 4094;  // OpenCV's CV_FS_MAX_LEN, less the two quotes
  std::string quoted = "\"";
  for (const char c : value) {
    const unsigned char byte = static_cast<unsigned char>(c);
    switch (c) {
      case '\\': quoted += "\\\\"; break;
      case '"': quoted += "\\\""; break;
      case '\n': quoted += "\\n"; break;
      case '\r': quoted += "\\r"; break;
      case '\t': quoted += "\\t"; break;
      default:
        if (byte < 0x20) {
          char hex[8];
          std::snprintf(hex, sizeof hex, "0x%02X", byte);
          throw Error(std::string("YAML cannot hold the ") + key + " '" + value +
                      "': OpenCV's FileStorage reads no control character " + hex + " back");
        }
        quoted += c;
    }
  }
  if (quoted.size() - 1 > kLongestString)
    throw Error(std::string("YAML cannot hold the ") + key + " '" + value +
                "': OpenCV's FileStorage reads strings of at most " +
                std::to_string(kLongestString) + " bytes, escapes counted");
  return quoted + "\"";
}

}  // namespace

// The source record comes right after "image", the options after "width" and "height" (a few
// KiB in; strings are escaped, so `"options":` cannot occur in a name); a complete file ends with
// the descriptor list and the closing brace.
OutputRecord json_file_record(const std::string& path, const SourceRecord& source) {
  constexpr std::size_t kHeadBytes = 64 * 1024;
  const std::string head = read_bytes(path, 0, kHeadBytes);
  OutputRecord record;
  record.of_source = read_bytes(path, 4, 4) == "]\n}\n" &&
                     head.find(source_json_fragment(source)) != std::string::npos;
  const std::size_t key = head.find("\"options\":");
  const std::size_t begin = head.find('{', key), end = head.find('}', key);
  if (key != std::string::npos && begin < end && end != std::string::npos)
    record.options = head.substr(begin, end + 1 - begin);
  return record;
}

OutputRecord yaml_file_record(const std::string& path, const SourceRecord& source) {
  // Read here and parsed from memory: OpenCV cannot open a file whose path holds a newline.
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  OutputRecord record;
  try {
    const cv::FileStorage fs(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
    if (!fs.isOpened()) return {};
    record.of_source =
        !fs["descriptors"].empty() && static_cast<std::string>(fs["source_name"]) == source.name &&
        static_cast<std::string>(fs["source_bytes"]) == std::to_string(source.bytes) &&
        static_cast<std::string>(fs["source_mtime_ns"]) == std::to_string(source.mtime_ns);
    if (fs["options"].isString()) record.options = static_cast<std::string>(fs["options"]);
  } catch (const cv::Exception&) {
    return {};
  }
  return record;
}

void check_yaml_can_hold(const std::string& image_path, const std::string& source_name) {
  yaml_quoted(image_path, "image name");
  yaml_quoted(source_name, "image name");
}

std::string features_json(const std::string& image_path, const Features& features,
                          const ExtractorOptions& options,
                          const std::optional<SourceRecord>& source) {
  std::ostringstream out;
  JsonWriter json(out);
  json.begin_object();
  json.field("image", image_path);
  if (source) write_source(json, *source);
  json.field("width", features.image_width).field("height", features.image_height);
  json.key("options");
  write_option_record(json, options);
  write_info(json, features.info, source ? &source->warnings : nullptr);
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

void write_features_json(const std::string& path, const std::string& image_path,
                         const Features& features, const ExtractorOptions& options,
                         const std::optional<SourceRecord>& source) {
  write_file_atomically(path, features_json(image_path, features, options, source));
}

void write_features_yaml(const std::string& path, const std::string& image_path,
                         const Features& features, const ExtractorOptions& options,
                         const std::optional<SourceRecord>& source) {
  std::vector<cv::KeyPoint> keypoints;
  keypoints.reserve(features.keypoints.size());
  for (const Keypoint& kp : features.keypoints)
    keypoints.emplace_back(cv::Point2f(kp.x, kp.y), kp.size, kp.angle_deg, kp.response, kp.octave,
                           -1);
  cv::Mat descriptors(static_cast<int>(features.descriptors.size()), kDescriptorBytes, CV_8U);
  for (int r = 0; r < descriptors.rows; ++r)
    std::copy(features.descriptors[static_cast<std::size_t>(r)].begin(),
              features.descriptors[static_cast<std::size_t>(r)].end(),
              descriptors.ptr<std::uint8_t>(r));
  // Written in memory, then by write_file_atomically: one temporary-file rule for every format.
  std::string text;
  try {
    cv::FileStorage fs(".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
    // Strings through cv::write, never operator<< (which reads "{..." and "[..." as structure).
    cv::write(fs, "image", yaml_quoted(image_path, "image name"));
    if (source) {
      cv::write(fs, "source_name", yaml_quoted(source->name, "image name"));
      cv::write(fs, "source_bytes", std::to_string(source->bytes));
      cv::write(fs, "source_mtime_ns", std::to_string(source->mtime_ns));
    }
    fs << "width" << features.image_width << "height" << features.image_height;
    cv::write(fs, "options", yaml_quoted(option_record_json(options), "option record"));
    cv::write(fs, "keypoints", keypoints);
    fs << "descriptors" << descriptors;
    text = fs.releaseAndGetString();
  } catch (const cv::Exception& e) {
    throw Error("cannot write '" + path + "': " + e.what());
  }
  write_file_atomically(path, text);
}

}  // namespace aief::io
