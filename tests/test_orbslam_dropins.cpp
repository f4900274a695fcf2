// What the ORB-SLAM2 and ORB-SLAM3 drop-ins share, tested once for both: the scale tables as each
// ORB-SLAM computes them, the five constructor numbers as options, and the pyramid their stereo
// matching reads. What differs (ORB-SLAM3's lapping area and returned count, ORB-SLAM2's settings
// in depth) is in tests/test_orbslam2_dropin.cpp and tests/test_orbslam3_dropin.cpp.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "aief/error.hpp"
#include "aief/orbslam2_extractor.hpp"
#include "aief/orbslam3_extractor.hpp"
#include "tests/test_support.hpp"

namespace aief {
namespace {

struct OrbSlam2 {
  using Extractor = ORBextractor;
  using ScaleFactorMember = float;  // ORB-SLAM2: `float scaleFactor;`
  static void run(Extractor& orb, const cv::Mat& image, std::vector<cv::KeyPoint>& keypoints,
                  cv::Mat& descriptors) {
    orb(image, cv::noArray(), keypoints, descriptors);
  }
};

struct OrbSlam3 {
  using Extractor = orbslam3::ORBextractor;
  using ScaleFactorMember = double;  // ORB-SLAM3: `double scaleFactor;`
  static void run(Extractor& orb, const cv::Mat& image, std::vector<cv::KeyPoint>& keypoints,
                  cv::Mat& descriptors) {
    std::vector<int> stereo_pinhole = {0, 0};
    orb(image, cv::noArray(), keypoints, descriptors, stereo_pinhole);
  }
};

template <class DropIn>
class OrbSlamDropIns : public testing::Test {};
using DropIns = testing::Types<OrbSlam2, OrbSlam3>;
TYPED_TEST_SUITE(OrbSlamDropIns, DropIns);

// The scale tables exactly as the ORBextractor constructor computes them: each level's factor
// in the type of ORB-SLAM's scaleFactor member, the tables in float.
TYPED_TEST(OrbSlamDropIns, AccessorsAsOrbSlam) {
  using Member = typename TypeParam::ScaleFactorMember;
  for (const float factor : {1.2f, 1.3f, 1.5f, 2.0f}) {
    for (const int levels : {1, 3, 8, 12}) {
      const typename TypeParam::Extractor orb(1000, factor, levels, 20, 7);
      const Member orbslam_scale_factor = factor;
      EXPECT_EQ(orb.GetLevels(), levels);
      EXPECT_EQ(orb.GetScaleFactor(), static_cast<float>(orbslam_scale_factor));
      std::vector<float> scale(static_cast<std::size_t>(levels)),
          sigma2(static_cast<std::size_t>(levels));
      scale[0] = 1.0f;
      sigma2[0] = 1.0f;
      for (std::size_t i = 1; i < scale.size(); ++i) {
        scale[i] = static_cast<float>(scale[i - 1] * orbslam_scale_factor);
        sigma2[i] = scale[i] * scale[i];
      }
      ASSERT_EQ(orb.GetScaleFactors().size(), scale.size());
      ASSERT_EQ(orb.GetInverseScaleFactors().size(), scale.size());
      ASSERT_EQ(orb.GetScaleSigmaSquares().size(), scale.size());
      ASSERT_EQ(orb.GetInverseScaleSigmaSquares().size(), scale.size());
      for (std::size_t i = 0; i < scale.size(); ++i) {
        SCOPED_TRACE("factor " + std::to_string(factor) + ", level " + std::to_string(i));
        EXPECT_EQ(orb.GetScaleFactors()[i], scale[i]);
        EXPECT_EQ(orb.GetInverseScaleFactors()[i], 1.0f / scale[i]);
        EXPECT_EQ(orb.GetScaleSigmaSquares()[i], sigma2[i]);
        EXPECT_EQ(orb.GetInverseScaleSigmaSquares()[i], 1.0f / sigma2[i]);
      }
    }
  }
}

TYPED_TEST(OrbSlamDropIns, ConstructorArgumentsBecomeTheOptions) {
  const typename TypeParam::Extractor orb(1234, 1.3f, 6, 25, 9);
  const ExtractorOptions& o = orb.extractor().options();
  EXPECT_EQ(o.n_features, 1234);
  EXPECT_EQ(o.scale_factor, static_cast<double>(1.3f));
  EXPECT_EQ(o.n_levels, 6);
  EXPECT_EQ(o.fast_threshold, 25);
  EXPECT_EQ(o.fast_min_threshold, 9);
  // ORB-SLAM's choices unless the settings name a mode (docs/slam.md, "Which choice costs what")
  EXPECT_EQ(o.distribution, Distribution::quadtree);
  EXPECT_EQ(o.entropy, EntropyMeasure::off);
  EXPECT_EQ(o.coordinates,
            CoordinateMap::scaled);  // ORB-SLAM's keypoint convention (docs/slam.md, "Stereo")
  EXPECT_FALSE(o.subpixel);
  EXPECT_TRUE(std::isinf(o.candidate_pool));  // spread over the frame (docs/slam.md, "Results")
  EXPECT_THROW(typename TypeParam::Extractor(1000, 0.8f, 8, 20, 7), Error);
}

// The pyramid ORB-SLAM's stereo matching reads: level 0 is the image, level n is
// round(size / scale_n) as ORB-SLAM sizes it, and is the engine's level; it follows the latest
// frame.
TYPED_TEST(OrbSlamDropIns, PyramidIsTheEnginesLevelsAtOrbSlamsSizes) {
  const cv::Mat gray = test::load_sample_gray("leuven", "img1.png");
  typename TypeParam::Extractor orb(800, 1.2f, 8, 20, 7);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  TypeParam::run(orb, gray, keypoints, descriptors);
  ASSERT_EQ(orb.mvImagePyramid.size(), 8u);
  EXPECT_EQ(cv::norm(orb.mvImagePyramid[0], gray, cv::NORM_INF), 0.0);
  for (int n = 1; n < 8; ++n) {
    const cv::Mat& level = orb.mvImagePyramid[static_cast<std::size_t>(n)];
    const float inverse = orb.GetInverseScaleFactors()[static_cast<std::size_t>(n)];
    EXPECT_EQ(level.cols, cvRound(static_cast<float>(gray.cols) * inverse)) << "level " << n;
    EXPECT_EQ(level.rows, cvRound(static_cast<float>(gray.rows) * inverse)) << "level " << n;
    EXPECT_EQ(static_cast<const void*>(level.data),
              static_cast<const void*>(orb.extractor().pyramid_level(n).data))
        << "level " << n;
  }
  const cv::Mat small = test::load_sample_gray("boat", "img1.png")(cv::Rect(0, 0, 200, 150));
  TypeParam::run(orb, small, keypoints, descriptors);
  EXPECT_EQ(orb.mvImagePyramid[0].cols, 200);
  EXPECT_EQ(orb.mvImagePyramid[0].rows, 150);
}

}  // namespace
}  // namespace aief
