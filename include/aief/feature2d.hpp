#pragma once
// aief as a cv::Feature2D (target aief::opencv): code written against cv::Ptr<cv::Feature2D>
// (cv::ORB::create() and friends, OpenCV's matchers and drawKeypoints, evaluation harnesses)
// takes aief by changing the line that creates the detector (docs/opencv.md):
//
//   cv::Ptr<cv::Feature2D> orb = aief::opencv::Feature2D::create();  // was cv::ORB::create()
//   orb->detectAndCompute(image, mask, keypoints, descriptors);
//
// Bit-exact with the engine: detectAndCompute gives Extractor::extract's keypoints and
// descriptors, compute gives Extractor::describe's, and detect + compute gives detectAndCompute.
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>

#include "aief/error.hpp"  // what the functions below throw
#include "aief/extractor.hpp"

namespace aief::opencv {

class Feature2D : public cv::Feature2D {
 public:
  // Validates the options (throws aief::Error). given_angles: what compute() does with the
  // angles of the keypoints it is given: keeps them, as cv::ORB::compute does (the default), or
  // recomputes them (the intensity centroid, as for detected keypoints).
  static cv::Ptr<Feature2D> create(const ExtractorOptions& options = {},
                                   GivenAngles given_angles = GivenAngles::keep);
  explicit Feature2D(const ExtractorOptions& options = {},
                     GivenAngles given_angles = GivenAngles::keep);

  // image: CV_8UC1, or CV_8UC3 / CV_8UC4 (BGR / BGRA, converted to gray as cv::cvtColor does).
  // mask (detection): CV_8UC1 of the image's size; keypoints are detected where it is non-zero,
  // and the feature budget is filled there (Extractor::extract with a mask). Ignored with
  // useProvidedKeypoints, as cv::ORB ignores it.
  // useProvidedKeypoints: the given keypoints are described (Extractor::describe): each keeps its
  // fields (class_id included), and its angle too unless the detector was made with
  // GivenAngles::recompute; those too close to their level's edge are removed from `keypoints`,
  // as cv::ORB::compute removes some.
  // descriptors: N x 32 CV_8U, released when there is no keypoint (as cv::ORB). Keypoints carry
  // pt (level-0 pixels), size, angle (degrees), response (FAST score), octave, class_id -1.
  // Throws aief::Error for an image or mask of another kind, or a keypoint octave outside
  // [0, n_levels).
  void detectAndCompute(cv::InputArray image, cv::InputArray mask,
                        std::vector<cv::KeyPoint>& keypoints, cv::OutputArray descriptors,
                        bool useProvidedKeypoints = false) override;

  int descriptorSize() const override { return kDescriptorBytes; }
  int descriptorType() const override { return CV_8U; }
  int defaultNorm() const override { return cv::NORM_HAMMING; }
  bool empty() const override { return false; }
  cv::String getDefaultName() const override { return "Feature2D.AIEF"; }

  // The options, one key per option as the output files record them
  // (core/options/option_table.hpp); read() takes any subset of the keys (the others keep their
  // value) and throws aief::Error for a bad value or a key it does not read (a typo, cv::ORB's
  // `nfeatures`: named, with aief's key where there is one), leaving the detector as it was.
  void write(cv::FileStorage& storage) const override;
  void read(const cv::FileNode& node) override;
  using cv::Feature2D::read;
  using cv::Feature2D::write;

  const ExtractorOptions& options() const { return extractor_.options(); }
  const Extractor& extractor() const { return extractor_; }

 private:
  Extractor extractor_;
  GivenAngles given_angles_;
  Features features_;
  cv::Mat gray_;
  std::vector<Keypoint> given_;
  std::vector<std::int32_t> kept_;
};

}  // namespace aief::opencv
