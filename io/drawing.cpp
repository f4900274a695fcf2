#include "io/drawing.hpp"

#include <cmath>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "aief/error.hpp"

namespace aief::io {

namespace {

cv::Mat color_copy(ImageView image) {
  const cv::Mat gray(image.height, image.width, CV_8UC1, const_cast<std::uint8_t*>(image.data),
                     static_cast<std::size_t>(image.stride));
  cv::Mat color;
  cv::cvtColor(gray, color, cv::COLOR_GRAY2BGR);
  return color;
}

void write_png(const std::string& path, const cv::Mat& picture) {
  bool ok = false;
  try {
    ok = cv::imwrite(path, picture);
  } catch (const cv::Exception& e) {
    throw Error("cannot write picture '" + path + "': " + e.err);
  }
  if (!ok)
    throw Error("cannot write picture '" + path +
                "' (is the extension .png and the folder writable?)");
}

cv::Scalar octave_color(int octave) {
  static const cv::Scalar palette[] = {{0, 255, 0},   {255, 200, 0}, {0, 200, 255}, {255, 0, 255},
                                       {0, 128, 255}, {255, 255, 0}, {128, 0, 255}, {0, 0, 255}};
  return palette[octave % 8];
}

}  // namespace

bool is_picture_file_name(const std::string& path) {
  try {
    return cv::haveImageWriter(path);
  } catch (const cv::Exception&) {  // no extension at all
    return false;
  }
}

void draw_keypoints_png(const std::string& path, ImageView image, const Features& features) {
  cv::Mat picture = color_copy(image);
  for (const Keypoint& kp : features.keypoints) {
    const cv::Point2f centre(kp.x, kp.y);
    const float radius = kp.size / 2;
    const cv::Scalar color = octave_color(kp.octave);
    cv::circle(picture, centre, static_cast<int>(std::lround(radius)), color, 1, cv::LINE_AA);
    const float angle = kp.angle_deg * static_cast<float>(CV_PI / 180.0);
    cv::line(picture, centre, centre + cv::Point2f(std::cos(angle), std::sin(angle)) * radius,
             color, 1, cv::LINE_AA);
  }
  write_png(path, picture);
}

void draw_matches_png(const std::string& path, ImageView a, const Features& features_a, ImageView b,
                      const Features& features_b, const std::vector<Match>& matches,
                      const std::vector<std::uint8_t>& inlier_mask) {
  const cv::Mat left = color_copy(a), right = color_copy(b);
  cv::Mat picture(std::max(left.rows, right.rows), left.cols + right.cols, CV_8UC3,
                  cv::Scalar::all(0));
  left.copyTo(picture(cv::Rect(0, 0, left.cols, left.rows)));
  right.copyTo(picture(cv::Rect(left.cols, 0, right.cols, right.rows)));
  const cv::Point2f offset(static_cast<float>(left.cols), 0);
  // Outliers first, so the inliers are drawn on top.
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t i = 0; i < matches.size(); ++i) {
      const bool inlier = i < inlier_mask.size() && inlier_mask[i];
      if (inlier != (pass == 1)) continue;
      const Keypoint& ka = features_a.keypoints[static_cast<std::size_t>(matches[i].query)];
      const Keypoint& kb = features_b.keypoints[static_cast<std::size_t>(matches[i].train)];
      const cv::Scalar color = inlier ? cv::Scalar(0, 220, 0) : cv::Scalar(0, 0, 255);
      cv::line(picture, cv::Point2f(ka.x, ka.y), cv::Point2f(kb.x, kb.y) + offset, color, 1,
               cv::LINE_AA);
    }
  }
  write_png(path, picture);
}

}  // namespace aief::io
