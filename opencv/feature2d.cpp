#include "aief/feature2d.hpp"

#include <cstdio>
#include <string>
#include <variant>

#include "aief/error.hpp"
#include "core/option_table.hpp"
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
  // Every option as the output files record it (core/option_table.hpp): numbers as numbers,
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

void Feature2D::read(const cv::FileNode& node) {
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
