#include "aief/feature2d.hpp"

#include <cstdio>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "aief/error.hpp"
#include "core/options/nearest_name.hpp"
#include "core/options/option_table.hpp"
#include "opencv/cv_conversions.hpp"

namespace aief::opencv {

namespace {

// The mask rule of cv::Feature2D: CV_8UC1 of the image's size (the engine checks the size).
ImageView mask_view(cv::InputArray mask) {
  if (mask.empty()) return {};
  const cv::Mat m = mask.getMat();
  if (m.type() != CV_8UC1) throw Error("mask must be CV_8UC1, got " + cv::typeToString(m.type()));
  return view_of(m);
}

Keypoint from_cv_keypoint(const cv::KeyPoint& kp) {
  Keypoint out;
  out.x = kp.pt.x;
  out.y = kp.pt.y;
  out.size = kp.size;
  out.angle_deg = kp.angle;
  out.response = kp.response;
  out.octave = kp.octave;
  return out;
}

}  // namespace

cv::Ptr<Feature2D> Feature2D::create(const ExtractorOptions& options, GivenAngles given_angles) {
  return cv::makePtr<Feature2D>(options, given_angles);
}

Feature2D::Feature2D(const ExtractorOptions& options, GivenAngles given_angles)
    : extractor_(options), given_angles_(given_angles) {}

void Feature2D::detectAndCompute(cv::InputArray image, cv::InputArray mask,
                                 std::vector<cv::KeyPoint>& keypoints, cv::OutputArray descriptors,
                                 bool useProvidedKeypoints) {
  const cv::Mat input = image.getMat();
  const cv::Mat& gray = detail::gray_of(input, gray_);
  if (useProvidedKeypoints) {
    given_.clear();
    given_.reserve(keypoints.size());
    for (const cv::KeyPoint& kp : keypoints) given_.push_back(from_cv_keypoint(kp));
    extractor_.describe(view_of(gray), given_, features_, &kept_, given_angles_);
    // The kept keypoints as given (class_id and all), with the angle the descriptor used.
    for (std::size_t k = 0; k < kept_.size(); ++k) {
      keypoints[k] = keypoints[static_cast<std::size_t>(kept_[k])];
      keypoints[k].angle = features_.keypoints[k].angle_deg;  // the given one when kept
    }
    keypoints.resize(kept_.size());
  } else {
    extractor_.extract(view_of(gray), mask_view(mask), features_);
    detail::fill_cv_keypoints(features_, keypoints);
  }
  if (descriptors.needed()) detail::fill_cv_descriptors(features_, descriptors, true);
}

void Feature2D::write(cv::FileStorage& storage) const {
  if (!storage.isOpened()) return;
  storage << "name" << getDefaultName();
  // Every option as the output files record it (core/options/option_table.hpp): numbers as numbers,
  // names and toggles as the text the table reads back.
  for (const auto& [key, value] : option_table::record_of(options())) {
    const std::string name(key);
    if (const auto* number = std::get_if<double>(&value))
      storage << name << *number;
    else if (const auto* integer = std::get_if<long long>(&value);
             integer && *integer == static_cast<int>(*integer))
      storage << name << static_cast<int>(*integer);
    else
      storage << name << option_table::text_of(option_table::row(key), value);
  }
}

namespace {

// cv::ORB's keys (what cv::ORB::write writes), each with what aief has instead.
constexpr std::pair<std::string_view, std::string_view> kCvOrbKeys[] = {
    {"nfeatures", "aief's key is n_features"},
    {"scaleFactor", "aief's key is scale_factor"},
    {"nlevels", "aief's key is n_levels"},
    {"fastThreshold", "aief's key is fast_threshold"},
    {"edgeThreshold", "aief's border is fixed (19 pixels, the rBRIEF patch's reach)"},
    {"patchSize", "aief's patch is fixed (31 pixels)"},
    {"firstLevel", "aief's pyramid starts at the image (level 0)"},
    {"wta_k", "aief's descriptor compares pairs (WTA_K 2)"},
    {"scoreType", "aief ranks by the FAST score"},
};

// Refuses a key read() would not read: a typo or another detector's setting left unread would
// leave the detector other than the file says, without a word.
void refuse_unknown_keys(const cv::FileNode& node) {
  if (!node.isMap()) return;
  for (auto it = node.begin(); it != node.end(); ++it) {
    const std::string key = (*it).name();
    if (key == "name") continue;  // write()'s getDefaultName()
    const option_table::OptionRow* row = nullptr;
    for (const option_table::OptionRow& r : option_table::rows())
      if (r.key == key) row = &r;
    if (row && row->is_field()) continue;
    for (const auto& [orb_key, instead] : kCvOrbKeys)
      if (key == orb_key)
        throw Error("Feature2D::read: '" + key + "' is cv::ORB's setting, not aief's (" +
                    std::string(instead) + ")");
    std::string keys;
    std::vector<std::string_view> known;
    for (const option_table::OptionRow& r : option_table::rows())
      if (r.is_field()) {
        keys += (keys.empty() ? "" : ", ") + std::string(r.key);
        known.push_back(r.key);
      }
    const std::string nearest = option_table::nearest_name(key, known);
    throw Error("Feature2D::read: unknown key '" + key + "'" +
                (nearest.empty() ? "" : " (did you mean " + nearest + "?)") +
                " (it reads what write() writes: " + keys + ")");
  }
}

}  // namespace

void Feature2D::read(const cv::FileNode& node) {
  refuse_unknown_keys(node);
  ExtractorOptions options = this->options();
  for (const option_table::OptionRow& row : option_table::rows()) {
    if (!row.is_field()) continue;
    const cv::FileNode value = node[std::string(row.key)];
    if (value.empty()) continue;
    std::string text;
    if (value.isInt()) {
      text = std::to_string(static_cast<int>(value));
    } else if (value.isReal()) {
      char buffer[40];
      std::snprintf(buffer, sizeof buffer, "%.17g", static_cast<double>(value));
      text = buffer;
    } else if (value.isString()) {
      text = static_cast<std::string>(value);
    } else {
      throw Error("setting " + std::string(row.key) + " is neither a number nor a string");
    }
    row.field.set(options, option_table::parse_value(row, text, row.key));
  }
  extractor_ = Extractor(options);  // validates; on an error the detector is left as it was
}

}  // namespace aief::opencv
