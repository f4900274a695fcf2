#include "tools/eval/methods.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>

#include <opencv2/features2d.hpp>

#include "aief/adapt.hpp"
#include "aief/cv_image_view.hpp"
#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "core/options/option_names.hpp"
#include "tools/eval/keypoint_metrics.hpp"

namespace aief::eval {

bool operator==(const Method& a, const Method& b) {
  if (a.baseline != Baseline::none || b.baseline != Baseline::none) return a.baseline == b.baseline;
  return a.mode == b.mode && a.threshold == b.threshold;
}

std::string method_name(const Method& method) {
  if (method.baseline == Baseline::opencv_orb) return "OpenCV ORB";
  if (method.baseline == Baseline::opencv_sift) return "OpenCV SIFT";
  if (method.baseline == Baseline::opencv_akaze) return "OpenCV AKAZE";
  if (method.baseline == Baseline::opencv_brisk) return "OpenCV BRISK";
  std::string name;
  switch (method.mode) {
    case Mode::orbslam2: name = "ORB-SLAM2 mode (ours)"; break;
    case Mode::faithful: name = "ORB-SLAM3 faithful mode (ours)"; break;
    case Mode::quadtree_entropy: name = "Quadtree + entropy (F = 4)"; break;
    case Mode::aief_paper: name = "AIEF paper"; break;
    case Mode::aief: name = "AIEF"; break;
    case Mode::quality: name = "AIEF quality mode"; break;
  }
  switch (method.threshold) {
    case ThresholdChoice::mode: return name;
    case ThresholdChoice::swept: return name + " (adaptive F)";
    case ThresholdChoice::automatic: return name + " (auto F, no pair)";
  }
  return name;
}

std::string method_key(const Method& method) {
  if (method.baseline == Baseline::opencv_orb) return "opencv_orb";
  if (method.baseline == Baseline::opencv_sift) return "opencv_sift";
  if (method.baseline == Baseline::opencv_akaze) return "opencv_akaze";
  if (method.baseline == Baseline::opencv_brisk) return "opencv_brisk";
  std::string key(to_string(method.mode));
  std::replace(key.begin(), key.end(), '-', '_');
  switch (method.threshold) {
    case ThresholdChoice::mode: return key;
    case ThresholdChoice::swept: return key + "_adaptive";
    case ThresholdChoice::automatic: return key + "_auto";
  }
  return key;
}

Method parse_method_key(const std::string& key) {
  for (const Method& method : kAllMethods)
    if (method_key(method) == key) return method;
  // Any mode with any way of choosing F, e.g. "aief" (F as the mode sets it) or "quality_auto".
  for (const auto& mode : option_names::Table<Mode>::names)
    for (ThresholdChoice threshold :
         {ThresholdChoice::mode, ThresholdChoice::swept, ThresholdChoice::automatic})
      if (const Method method{mode.value, threshold}; method_key(method) == key) return method;
  throw Error("unknown method '" + key + "'");
}

namespace {

// Matched point pairs, then every metric from them, the same for every method.
void measure(const std::vector<Point2>& pa, const std::vector<Point2>& pb, const Homography& truth,
             int width, int height, PairResult& r) {
  r.putative = static_cast<int>(pa.size());
  const HomographyResult model = find_homography_ransac(pa, pb);
  r.inliers = model.found ? model.inliers : 0;
  r.cmr = r.putative > 0 ? static_cast<double>(r.inliers) / r.putative : 0.0;
  r.correct = 0;
  int within_1px = 0, within_2px = 0;
  for (std::size_t i = 0; i < pa.size(); ++i) {
    const Point2 p = apply_homography(truth, pa[i]);
    const double error = std::hypot(p.x - pb[i].x, p.y - pb[i].y);
    r.correct += error <= 3.0 ? 1 : 0;
    within_2px += error <= 2.0 ? 1 : 0;
    within_1px += error <= 1.0 ? 1 : 0;
  }
  const auto share = [&](int count) {
    return r.putative > 0 ? static_cast<double>(count) / r.putative : 0.0;
  };
  r.accuracy = share(r.correct);
  r.accuracy_2px = share(within_2px);
  r.accuracy_1px = share(within_1px);
  if (model.found) {
    r.corner_error = mean_corner_error(model.H, truth, width, height);
    r.homography_ok = r.corner_error < 5.0;
  }
}

// Repeatability and spread from the keypoints alone.
void measure_keypoints(const std::vector<Point2>& a, const std::vector<Point2>& b,
                       const Homography& truth, int width, int height, int width_b, int height_b,
                       PairResult& r) {
  r.keypoints_a = static_cast<int>(a.size());
  r.keypoints_b = static_cast<int>(b.size());
  r.repeatability = repeatability(a, b, truth, width, height, width_b, height_b);
  r.spread = keypoint_spread(a, width, height);
}

std::vector<Point2> points_of(const Features& features) {
  std::vector<Point2> points;
  for (const Keypoint& kp : features.keypoints) points.push_back({kp.x, kp.y});
  return points;
}

void measure_features(const Features& a, const Features& b, const std::vector<Match>& matches,
                      const Homography& truth, int width, int height, PairResult& r) {
  std::vector<Point2> pa, pb;
  for (const Match& m : matches) {
    const Keypoint& ka = a.keypoints[static_cast<std::size_t>(m.query)];
    const Keypoint& kb = b.keypoints[static_cast<std::size_t>(m.train)];
    pa.push_back({ka.x, ka.y});
    pb.push_back({kb.x, kb.y});
  }
  measure_keypoints(points_of(a), points_of(b), truth, width, height, b.image_width, b.image_height,
                    r);
  measure(pa, pb, truth, width, height, r);
}

// The options of an engine row: the aief mode's rows take the evaluation's (its flags), the
// others their mode's; one thread.
ExtractorOptions options_of(const Method& method, const EvalSettings& s) {
  ExtractorOptions options =
      method.mode == Mode::aief ? s.aief : options_for_mode(method.mode, ExtractorOptions{});
  if (method.threshold == ThresholdChoice::automatic) options.auto_threshold = true;
  options.threads = 1;  // per-core times, as the paper's and OpenCV's
  return options;
}

constexpr int kBaselineFeatures = 1000;  // every row's count

cv::Ptr<cv::Feature2D> opencv_detector(Baseline baseline) {
  if (baseline == Baseline::opencv_orb) return cv::ORB::create(kBaselineFeatures, 1.2f, 8);
  if (baseline == Baseline::opencv_akaze) return cv::AKAZE::create();
  if (baseline == Baseline::opencv_brisk) return cv::BRISK::create();
  return cv::SIFT::create(kBaselineFeatures);
}

// Keypoints and descriptors of one image as the baseline gives them; AKAZE and BRISK, which take
// no count, keep their kBaselineFeatures strongest before describing.
void opencv_features(Baseline baseline, const cv::Ptr<cv::Feature2D>& detector, const cv::Mat& gray,
                     std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors) {
  if (baseline == Baseline::opencv_akaze || baseline == Baseline::opencv_brisk) {
    detector->detect(gray, keypoints);
    cv::KeyPointsFilter::retainBest(keypoints, kBaselineFeatures);
    detector->compute(gray, keypoints, descriptors);
    return;
  }
  detector->detectAndCompute(gray, cv::noArray(), keypoints, descriptors);
}

PairResult run_ours(const Method& method, const cv::Mat& a, const cv::Mat& b,
                    const Homography& truth, const EvalSettings& s) {
  PairResult r;
  const ExtractorOptions options = options_of(method, s);
  if (method.threshold == ThresholdChoice::swept) {
    SweepOptions sweep;
    sweep.match = s.match;
    const auto start = std::chrono::steady_clock::now();
    const AdaptResult adapted = adapt(view_of(a), view_of(b), options, sweep);
    r.sweep_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    measure_features(adapted.features_a, adapted.features_b, adapted.matches, truth, a.cols, a.rows,
                     r);
    r.threshold = adapted.threshold;
    return r;
  }
  Extractor extractor(options);
  Features fa, fb;
  extractor.extract(view_of(a), fa);
  extractor.extract(view_of(b), fb);
  const std::vector<Match> matches = match_descriptors(fa.descriptors, fb.descriptors, s.match);
  measure_features(fa, fb, matches, truth, a.cols, a.rows, r);
  if (options.entropy != EntropyMeasure::off) r.threshold = fa.info.entropy_threshold_used;
  return r;
}

PairResult run_opencv(Baseline baseline, const cv::Mat& a, const cv::Mat& b,
                      const Homography& truth, const EvalSettings& s) {
  PairResult r;
  const cv::Ptr<cv::Feature2D> detector = opencv_detector(baseline);
  std::vector<cv::KeyPoint> ka, kb;
  cv::Mat da, db;
  opencv_features(baseline, detector, a, ka, da);
  opencv_features(baseline, detector, b, kb, db);
  const auto points = [](const std::vector<cv::KeyPoint>& keypoints) {
    std::vector<Point2> out;
    for (const cv::KeyPoint& kp : keypoints) out.push_back({kp.pt.x, kp.pt.y});
    return out;
  };
  measure_keypoints(points(ka), points(kb), truth, a.cols, a.rows, b.cols, b.rows, r);

  std::vector<Point2> pa, pb;
  if (baseline == Baseline::opencv_orb) {
    // Binary descriptors: our matcher, so the rows differ only in their features.
    const auto to_descriptors = [](const cv::Mat& m) {
      std::vector<Descriptor> out(static_cast<std::size_t>(m.rows));
      for (int row = 0; row < m.rows; ++row)
        std::copy_n(m.ptr<std::uint8_t>(row), 32, out[static_cast<std::size_t>(row)].begin());
      return out;
    };
    for (const Match& m : match_descriptors(to_descriptors(da), to_descriptors(db), s.match)) {
      pa.push_back(
          {ka[static_cast<std::size_t>(m.query)].pt.x, ka[static_cast<std::size_t>(m.query)].pt.y});
      pb.push_back(
          {kb[static_cast<std::size_t>(m.train)].pt.x, kb[static_cast<std::size_t>(m.train)].pt.y});
    }
  } else if (!da.empty() && !db.empty()) {
    // SIFT's float descriptors by L2, AKAZE's and BRISK's binary ones by Hamming: mutual
    // nearest neighbours (cross-check); Lowe's ratio when asked, and both for mutual_ratio.
    const int norm = baseline == Baseline::opencv_sift ? cv::NORM_L2 : cv::NORM_HAMMING;
    std::vector<cv::DMatch> matches;
    if (s.match.kind == MatcherKind::ratio || s.match.kind == MatcherKind::mutual_ratio) {
      std::vector<cv::DMatch> backward;  // each train's nearest query
      if (s.match.kind == MatcherKind::mutual_ratio) cv::BFMatcher(norm).match(db, da, backward);
      std::vector<std::vector<cv::DMatch>> knn;
      cv::BFMatcher(norm).knnMatch(da, db, knn, 2);
      for (const auto& pair : knn)
        if (pair.size() == 2 && pair[0].distance < s.match.ratio * pair[1].distance &&
            (backward.empty() ||
             backward[static_cast<std::size_t>(pair[0].trainIdx)].trainIdx == pair[0].queryIdx))
          matches.push_back(pair[0]);
    } else {
      cv::BFMatcher(norm, true).match(da, db, matches);
    }
    for (const cv::DMatch& m : matches) {
      pa.push_back({ka[static_cast<std::size_t>(m.queryIdx)].pt.x,
                    ka[static_cast<std::size_t>(m.queryIdx)].pt.y});
      pb.push_back({kb[static_cast<std::size_t>(m.trainIdx)].pt.x,
                    kb[static_cast<std::size_t>(m.trainIdx)].pt.y});
    }
  }
  measure(pa, pb, truth, a.cols, a.rows, r);
  return r;
}

}  // namespace

PairResult run_method(const Method& method, const cv::Mat& gray_a, const cv::Mat& gray_b,
                      const Homography& truth, const EvalSettings& settings) {
  if (method.baseline != Baseline::none)
    return run_opencv(method.baseline, gray_a, gray_b, truth, settings);
  return run_ours(method, gray_a, gray_b, truth, settings);
}

void time_extractions(const std::vector<Method>& methods, const cv::Mat& gray_a,
                      const EvalSettings& settings, std::vector<PairResult>& row,
                      MachineLoad& load) {
  // Each method's extractor and outputs live as long as its rounds: only the extraction is timed.
  std::vector<std::function<void()>> work;
  for (std::size_t m = 0; m < methods.size(); ++m) {
    if (methods[m].baseline != Baseline::none) {
      const Baseline baseline = methods[m].baseline;
      auto detector = opencv_detector(baseline);
      auto keypoints = std::make_shared<std::vector<cv::KeyPoint>>();
      auto descriptors = std::make_shared<cv::Mat>();
      work.push_back(
          [=] { opencv_features(baseline, detector, gray_a, *keypoints, *descriptors); });
    } else {
      ExtractorOptions options = options_of(methods[m], settings);
      if (methods[m].threshold == ThresholdChoice::swept)
        options.entropy_threshold = row[m].threshold;  // one frame at the learned F
      auto extractor = std::make_shared<Extractor>(options);
      auto features = std::make_shared<Features>();
      work.push_back([=] { extractor->extract(view_of(gray_a), *features); });
    }
  }
  load.sample();
  const std::vector<MethodTimes> times = time_interleaved(work, settings.timing_repeats);
  load.sample();
  for (std::size_t m = 0; m < methods.size(); ++m) {
    row[m].extract_ms = times[m].cpu.median_ms;
    row[m].extract_min_ms = times[m].cpu.min_ms;
    row[m].extract_max_ms = times[m].cpu.max_ms;
    row[m].extract_wall_ms = times[m].wall.median_ms;
  }
}

}  // namespace aief::eval
