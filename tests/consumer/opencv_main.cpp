// The installed adapter: a colour cv::Mat through aief::cv_extract and through the ORB-SLAM2
// drop-in; both must find keypoints, agree with each other and give N x 32 CV_8U descriptors.
#include <cstdio>
#include <cstring>
#include <vector>

#include <opencv2/core.hpp>

#include <aief/opencv.hpp>
#include <aief/orbslam2_extractor.hpp>

int main() {
  cv::Mat image(240, 320, CV_8UC3);
  cv::theRNG().state = 7;
  cv::randu(image, cv::Scalar::all(0), cv::Scalar::all(255));
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x)
      if ((x / 16 + y / 16) % 2) image.at<cv::Vec3b>(y, x) = cv::Vec3b(0, 0, 0);

  std::vector<cv::KeyPoint> keypoints, orb_keypoints;
  cv::Mat descriptors, orb_descriptors;
  // The drop-ins' options: orbslam2 mode (docs/slam.md, "Which choice costs what").
  aief::ExtractorOptions options = aief::options_for_mode(aief::Mode::orbslam2);
  options.n_features = 300;
  aief::cv_extract(image, keypoints, descriptors, options);
  aief::ORBextractor orb(300, 1.2f, 8, 20, 7);
  orb(image, cv::noArray(), orb_keypoints, orb_descriptors);
  std::printf("aief::opencv: %zu keypoints, descriptors %dx%d; ORBextractor: %zu keypoints\n",
              keypoints.size(), descriptors.rows, descriptors.cols, orb_keypoints.size());
  const bool same = keypoints.size() == orb_keypoints.size() &&
                    descriptors.size() == orb_descriptors.size() &&
                    std::memcmp(descriptors.data, orb_descriptors.data, descriptors.total()) == 0;
  const bool ok = !keypoints.empty() && descriptors.type() == CV_8U && descriptors.cols == 32 &&
                  descriptors.rows == static_cast<int>(keypoints.size()) && same;
  return ok ? 0 : 1;
}
