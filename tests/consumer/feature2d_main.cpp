// aief as a cv::Feature2D, compiled against the installed package: the same function runs
// cv::ORB and aief::opencv::Feature2D through cv::Ptr<cv::Feature2D>, line for line; only the
// line that creates the detector differs (docs/opencv.md).
#include <cstdio>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include <aief/feature2d.hpp>

namespace {

// What a program written for cv::ORB does with it.
bool run(const cv::Ptr<cv::Feature2D>& detector, const cv::Mat& image, const cv::Mat& moved) {
  cv::Mat mask(image.size(), CV_8UC1, cv::Scalar(0));
  mask(cv::Rect(0, 0, image.cols / 2, image.rows)).setTo(255);
  std::vector<cv::KeyPoint> keypoints, masked, moved_keypoints;
  cv::Mat descriptors, moved_descriptors;
  detector->detectAndCompute(image, cv::noArray(), keypoints, descriptors);
  detector->detect(image, masked, mask);
  detector->detect(moved, moved_keypoints);
  detector->compute(moved, moved_keypoints, moved_descriptors);
  cv::BFMatcher matcher(detector->defaultNorm(), true);
  std::vector<cv::DMatch> matches;
  matcher.match(descriptors, moved_descriptors, matches);
  cv::Mat canvas;
  cv::drawKeypoints(image, keypoints, canvas);
  cv::FileStorage storage("settings.yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  detector->write(storage);
  const cv::String settings = storage.releaseAndGetString();
  int inside = 0;
  for (const cv::KeyPoint& kp : masked) inside += kp.pt.x < image.cols / 2;
  std::printf(
      "%s: %zu keypoints (%zu, %d inside, with the left half masked), descriptors %dx%d %s, %zu "
      "cross-checked matches, "
      "%zu settings bytes\n",
      detector->getDefaultName().c_str(), keypoints.size(), masked.size(), inside, descriptors.rows,
      descriptors.cols,
      descriptors.type() == detector->descriptorType() ? "of its type" : "of another type",
      matches.size(), settings.size());
  return !keypoints.empty() && descriptors.cols == detector->descriptorSize() && !masked.empty() &&
         inside == static_cast<int>(masked.size()) && matches.size() > keypoints.size() / 4 &&
         !canvas.empty();
}

}  // namespace

int main() {
  cv::Mat image(480, 640, CV_8UC1);
  cv::theRNG().state = 5;
  cv::randu(image, cv::Scalar(0), cv::Scalar(255));
  cv::GaussianBlur(image, image, cv::Size(0, 0), 3);
  cv::normalize(image, image, 0, 255, cv::NORM_MINMAX);
  cv::Mat moved;
  cv::warpAffine(image, moved, cv::getRotationMatrix2D(cv::Point2f(320, 240), 10, 1.0),
                 image.size());

  const cv::Ptr<cv::Feature2D> orb = cv::ORB::create(1000);
  const cv::Ptr<cv::Feature2D> aief =
      aief::opencv::Feature2D::create();  // the one line that changes
  const bool ok = run(orb, image, moved) && run(aief, image, moved);
  return ok ? 0 : 1;
}
