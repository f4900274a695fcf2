#include "aief/orbslam_extractor_base.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "aief/error.hpp"
#include "core/options/nearest_name.hpp"
#include "core/options/option_names.hpp"
#include "core/options/option_table.hpp"
#include "opencv/cv_conversions.hpp"

namespace aief {

namespace {

// The drop-ins' defaults beside the mode (each drop-in names its mode: kDefaultMode), measured
// inside ORB-SLAM3 (docs/slam.md): no candidate pool in any mode, since it left half of
// ORB-SLAM3's grid cells empty and made its stereo trajectories 2-5x worse ("Results").

// Where keypoints sit. For a stereo rig or a depth camera, where ORB-SLAM puts them: level pixel
// x (an integer) at x * scale_n in level 0. Frame::ComputeStereoMatches (ORB-SLAM2 and ORB-SLAM3)
// centres its SAD window at round(x / scale_n) in mvImagePyramid and takes the disparity from x
// itself, so a sub-pixel or pixel-centre x shifts that keypoint's disparity by
// x - scale_n * round(x / scale_n): up to half a level pixel, times scale_n ("Stereo"). A
// monocular camera reads no disparity, and there the engine's own convention (pixel-centre map,
// sub-pixel peak: where the pyramid really sampled the point) initialises and tracks as ORB-SLAM3's
// own extractor does, where ORB-SLAM's convention lost tracking in every baseline run ("The
// keypoint convention in monocular").
ExtractorOptions with_keypoint_convention(ExtractorOptions options, bool stereo_or_depth) {
  options.coordinates = stereo_or_depth ? CoordinateMap::scaled : CoordinateMap::pixel_centre;
  options.subpixel = !stereo_or_depth;
  options.candidate_pool = std::numeric_limits<double>::infinity();
  return options;
}

// Whether ORB-SLAM settings describe a stereo rig or a depth camera: the keys of a second camera,
// a baseline or a depth scale, in either settings format (ORB-SLAM2 and ORB-SLAM3 before 1.0:
// Camera.bf, ThDepth, DepthMapFactor; ORB-SLAM3 1.0: Camera2.*, Stereo.*, RGBD.*).
bool describes_stereo_or_depth(const cv::FileStorage& settings) {
  for (const char* key : {"Camera.bf", "ThDepth", "DepthMapFactor", "Camera2.fx", "Stereo.b",
                          "Stereo.ThDepth", "Stereo.T_c1_c2", "RGBD.DepthMapFactor"})
    if (!settings[key].empty()) return true;
  return false;
}

ExtractorOptions orbslam_options(int nfeatures, float scaleFactor, int nlevels, int iniThFAST,
                                 int minThFAST, Mode mode) {
  // No settings to tell the sensor: ORB-SLAM's convention, which stereo needs.
  ExtractorOptions options =
      with_keypoint_convention(options_for_mode(mode), /*stereo_or_depth=*/true);
  options.n_features = nfeatures;
  options.scale_factor = scaleFactor;
  options.n_levels = nlevels;
  options.fast_threshold = iniThFAST;
  options.fast_min_threshold = minThFAST;
  return options;
}

// A settings value as the text the option table parses: FileStorage keeps numbers as int or
// double (written back by their shortest round-trip text), names and words as strings. What
// FileStorage cannot give back as written is said so: its integers are 32-bit (2147483648 reads
// as -2147483648, 2^32 as 0), an empty value reads as the string "...", and .nan is shown as
// YAML writes it (not "-nan").
std::string text_of_node(const cv::FileNode& node, const option_table::OptionRow& row,
                         const std::string& key) {
  if (node.isInt()) {
    const int value = static_cast<int>(node);
    if (row.kind() == option_table::ValueKind::integer && (value < row.low || value > row.high))
      throw Error(key + " expects " + option_table::expected_values(row) + ", got " +
                  std::to_string(value) +
                  " as OpenCV's settings reader reads it (it keeps integers in 32 bits: "
                  "2147483648 reads as -2147483648, 4294967296 as 0)");
    return std::to_string(value);
  }
  if (node.isReal()) {
    const double value = node.real();
    if (std::isnan(value)) return ".nan";
    char buffer[32];
    return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
  }
  if (node.isString()) {
    const std::string text = static_cast<std::string>(node);
    if (text == "...")  // what FileStorage makes of "key:" with nothing after it
      throw Error(key + " has no value (write one, or leave the key out for the default)");
    return text;
  }
  throw Error(key + " must be a number or a name, not a list or a map");
}

}  // namespace

OrbSlamExtractorBase::OrbSlamExtractorBase(int nfeatures, float scaleFactor, int nlevels,
                                           int iniThFAST, int minThFAST, Mode mode)
    : OrbSlamExtractorBase(
          orbslam_options(nfeatures, scaleFactor, nlevels, iniThFAST, minThFAST, mode)) {}

OrbSlamExtractorBase::OrbSlamExtractorBase(const ExtractorOptions& options)
    : extractor_(options),
      nlevels(options.n_levels),
      scaleFactor(static_cast<float>(options.scale_factor)) {
  compute_scales();
}

void OrbSlamExtractorBase::compute_scales() {
  // As ORB-SLAM's constructor: float products, sigma^2 = scale^2. (ORB-SLAM3 keeps scaleFactor
  // as a double, but the product of two floats is exact in double, so rounding it to float
  // gives the float product: the same tables.)
  const auto levels = static_cast<std::size_t>(nlevels);
  mvScaleFactor.assign(levels, 1.0f);
  mvLevelSigma2.assign(levels, 1.0f);
  for (std::size_t i = 1; i < levels; ++i) {
    mvScaleFactor[i] = mvScaleFactor[i - 1] * scaleFactor;
    mvLevelSigma2[i] = mvScaleFactor[i] * mvScaleFactor[i];
  }
  mvInvScaleFactor.resize(levels);
  mvInvLevelSigma2.resize(levels);
  for (std::size_t i = 0; i < levels; ++i) {
    mvInvScaleFactor[i] = 1.0f / mvScaleFactor[i];
    mvInvLevelSigma2[i] = 1.0f / mvLevelSigma2[i];
  }
}

namespace {

// An ORBextractor.* key no row reads: a misspelt key would leave the extractor other than the
// settings say, without a word (ORBextractor.entropyTreshold: 2.5 ran with F = 4).
void refuse_unknown_orbextractor_keys(const cv::FileStorage& settings) {
  constexpr std::string_view kPrefix = "ORBextractor.";
  const cv::FileNode root = settings.root();
  if (!root.isMap()) return;
  std::vector<std::string_view> known, earlier;  // earlier spellings are read, never suggested
  for (const option_table::OptionRow& row : option_table::rows()) {
    if (!row.yaml_key.empty()) known.push_back(row.yaml_key);
    if (!row.old_yaml_key.empty()) earlier.push_back(row.old_yaml_key);
  }
  for (const std::string& key : root.keys()) {
    // The prefix in another case (ORBExtractor., orbextractor.): ORB-SLAM reads none of them, and
    // they were skipped as another section's keys, silently.
    const bool prefixed_in_any_case =
        key.size() > kPrefix.size() &&
        std::equal(kPrefix.begin(), kPrefix.end(), key.begin(), [](char a, char b) {
          return std::tolower(static_cast<unsigned char>(a)) ==
                 std::tolower(static_cast<unsigned char>(b));
        });
    if (prefixed_in_any_case && key.compare(0, kPrefix.size(), kPrefix) != 0)
      throw Error("unknown setting '" + key + "': ORB-SLAM's extractor keys begin with '" +
                  std::string(kPrefix) + "', in this case exactly (did you mean " +
                  std::string(kPrefix) + key.substr(kPrefix.size()) + "?)");
    if (key.compare(0, kPrefix.size(), kPrefix) != 0 ||
        std::find(known.begin(), known.end(), key) != known.end() ||
        std::find(earlier.begin(), earlier.end(), key) != earlier.end())
      continue;
    const std::string nearest = option_table::nearest_name(key, known);
    std::string listed;
    for (std::string_view k : known) listed += (listed.empty() ? "" : ", ") + std::string(k);
    throw Error("unknown setting '" + key + "'" +
                (nearest.empty() ? "" : " (did you mean " + nearest + "?)") +
                "; the ORBextractor keys aief reads: " + listed);
  }
}

}  // namespace

ExtractorOptions OrbSlamExtractorBase::options_from_settings(const cv::FileStorage& settings,
                                                             Mode default_mode) {
  if (!settings.isOpened()) throw Error("settings file is not open");
  refuse_unknown_orbextractor_keys(settings);
  std::vector<option_table::GivenOption> given;
  for (const option_table::OptionRow& row : option_table::rows()) {
    if (!row.has_front_ends()) continue;
    for (std::string_view spelling : {row.yaml_key, row.old_yaml_key}) {  // the earlier: still read
      const std::string key(spelling);
      if (key.empty()) continue;
      if (const cv::FileNode node = settings[key]; !node.empty()) {
        given.push_back({&row, text_of_node(node, row, key), key});
        break;
      }
    }
  }
  // The drop-ins' own defaults over the mode's (with_keypoint_convention for this sensor), unless
  // set; their mode unless the settings name one.
  const auto is_given = [&](std::string_view key) {
    const option_table::OptionRow& row = option_table::row(key);
    return std::any_of(given.begin(), given.end(), [&](const auto& g) { return g.row == &row; });
  };
  const bool mode_given = is_given("mode");
  if (!mode_given) {
    const option_table::OptionRow& row = option_table::row("mode");
    given.push_back(
        {&row, std::string(option_names::name_of(default_mode)), std::string(row.yaml_key)});
  }
  const ExtractorOptions convention =
      with_keypoint_convention({}, describes_stereo_or_depth(settings));
  for (const char* key : {"coordinates", "subpixel", "candidate_pool"}) {
    if (is_given(key)) continue;
    const option_table::OptionRow& row = option_table::row(key);
    given.push_back(
        {&row, option_table::text_of(row, row.field.get(convention)), std::string(row.yaml_key)});
  }
  ExtractorOptions options;
  try {
    options = option_table::resolve_options(given);
  } catch (const Error& e) {
    // A refusal by the mode the settings did not name says which mode that was.
    const std::string mode_key(option_table::row("mode").yaml_key);
    if (mode_given || std::string(e.what()).find(mode_key) == std::string::npos) throw;
    throw Error(
        std::string(e.what()) + " (ORBextractor.mode is \"" +
        std::string(option_names::name_of(default_mode)) +
        "\" when the settings name none; the AIEF options need ORBextractor.mode: \"aief\")");
  }
  // Both versions' Tracking read scaleFactor into a float: so do we, so that settings and the
  // five-number constructor give the same extractor.
  options.scale_factor = static_cast<float>(options.scale_factor);
  options.validate();
  return options;
}

const Features& OrbSlamExtractorBase::extract_frame(cv::InputArray image) {
  const cv::Mat input = image.getMat();  // named: gray_of may return a reference to it
  const cv::Mat& gray = detail::gray_of(input, gray_);
  extractor_.extract(view_of(gray), features_);
  mvImagePyramid.resize(static_cast<std::size_t>(nlevels));
  // Level 0 is the gray input itself (sharing its reference count, so it outlives the caller's
  // Mat); the others are headers over the extractor's buffers, valid until the next call.
  mvImagePyramid[0] = gray;
  for (int n = 1; n < nlevels; ++n) {
    const ImageView level = extractor_.pyramid_level(n);
    mvImagePyramid[static_cast<std::size_t>(n)] =
        level.empty()
            ? cv::Mat()
            : cv::Mat(level.height, level.width, CV_8UC1, const_cast<std::uint8_t*>(level.data),
                      static_cast<std::size_t>(level.stride));
  }
  return features_;
}

}  // namespace aief
