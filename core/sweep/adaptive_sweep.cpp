#include "core/sweep/adaptive_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "aief/error.hpp"
#include "core/frame/frame_pipeline.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/match/matcher.hpp"
#include "core/sweep/sorted_block_entropies.hpp"
#include "core/sweep/sweep_matcher.hpp"
#include "core/sweep/sweep_runs.hpp"
#include "parallel/scheduler.hpp"

namespace aief {

namespace {

// Identity of candidate i of level n: candidate indices numbered on through the levels. The
// candidates are all detected by FramePipeline::analyse, so the numbering holds for every
// threshold.
std::vector<std::int32_t> level_id_offsets(const FrameAnalysis& analysis) {
  std::vector<std::int32_t> offsets(static_cast<std::size_t>(analysis.level_count()));
  std::size_t next = 0;
  for (int n = 0; n < analysis.level_count(); ++n) {
    offsets[static_cast<std::size_t>(n)] = static_cast<std::int32_t>(next);
    next += analysis.blocks(n).candidates.size();
  }
  if (next > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw Error("adapt: too many candidates");
  return offsets;
}

bool same_features(const Features& x, const Features& y) {
  if (x.keypoints.size() != y.keypoints.size() || x.descriptors != y.descriptors) return false;
  for (std::size_t k = 0; k < x.keypoints.size(); ++k)
    if (x.keypoints[k].x != y.keypoints[k].x || x.keypoints[k].y != y.keypoints[k].y ||
        x.keypoints[k].octave != y.keypoints[k].octave)
      return false;
  return true;
}

void homography_of(const Features& a, const Features& b, const std::vector<Match>& matches,
                   const RansacOptions& ransac, std::vector<Point2>& src, std::vector<Point2>& dst,
                   HomographyResult& out) {
  src.clear();
  dst.clear();
  for (const Match& m : matches) {
    const Keypoint& ka = a.keypoints[static_cast<std::size_t>(m.query)];
    const Keypoint& kb = b.keypoints[static_cast<std::size_t>(m.train)];
    src.push_back({ka.x, ka.y});
    dst.push_back({kb.x, kb.y});
  }
  out = find_homography_ransac(src, dst, ransac);
}

void check_sweep_inputs(const ExtractorOptions& options, const SweepOptions& sweep) {
  options.validate();
  sweep.validate();
  if (options.entropy == EntropyMeasure::off)
    throw Error("adapt needs an entropy measure (histogram or intensity), got entropy = off");
}

}  // namespace

SweepPipeline::SweepPipeline(const ExtractorOptions& options, const SweepOptions& sweep,
                             const KernelTable& kernels)
    : options_(options),
      sweep_(sweep),
      kernels_(&kernels),
      frame_a_(options, kernels, 1),
      frame_b_(options, kernels, 1) {
  check_sweep_inputs(options_, sweep_);
  scheduler_ = parallel::Scheduler(options_.threads);
}

FramePipeline& SweepPipeline::frame(int image) { return image == 0 ? frame_a_ : frame_b_; }

void SweepPipeline::analyse(int image, ImageView view) {
  frame(image).analyse(view, sweep_.first_threshold);
}

int SweepPipeline::begin_thresholds(Repeats repeats) {
  repeats_ = repeats;
  features_.image_entropy_bits = frame_a_.analysis().image_entropy_bits();
  // C = ceil(E / S_p) thresholds F_0 + c S_p (Eq. 11); at least one.
  const int cycles =
      std::max(1, static_cast<int>(std::ceil(features_.image_entropy_bits / sweep_.step)));
  // The features of each threshold keep their storage from pair to pair.
  features_.a.resize(static_cast<std::size_t>(cycles));
  features_.b.resize(static_cast<std::size_t>(cycles));
  for (int image = 0; image < 2; ++image) {
    const FrameAnalysis& analysis = frame(image).analysis();
    id_offsets_[static_cast<std::size_t>(image)] = level_id_offsets(analysis);
    sorted_entropies_[static_cast<std::size_t>(image)] = SortedBlockEntropies(analysis);
  }
  return cycles;
}

bool SweepPipeline::selects_like_previous(int image, int c) const {
  // select() reads the threshold only through the mask.
  return c > 0 && sorted_entropies_[static_cast<std::size_t>(image)].same_blocks_kept(
                      threshold_at(c - 1), threshold_at(c));
}

void SweepPipeline::repeat_previous(int image, int c) {
  std::vector<ThresholdFeatures>& features = image == 0 ? features_.a : features_.b;
  ThresholdFeatures& here = features[static_cast<std::size_t>(c)];
  const ThresholdFeatures& before = features[static_cast<std::size_t>(c - 1)];
  if (repeats_ == Repeats::copied) {
    here = before;
  } else {
    here.features.info = before.features.info;
    here.repeat_of = before.repeat_of >= 0 ? before.repeat_of : c - 1;
  }
  here.features.info.entropy_threshold_requested = threshold_at(c);
  here.features.info.entropy_threshold_used = threshold_at(c);
}

// Level n of one image at threshold F (no threshold fallback: the sweep measures each F as it
// is). A level whose kept blocks did not change since the previous threshold keeps its selection.
void SweepPipeline::choose_level(int image, int c, int n) {
  const std::size_t i = static_cast<std::size_t>(image);
  std::vector<std::vector<std::int32_t>>& chosen = chosen_[i];
  chosen.resize(static_cast<std::size_t>(frame(image).analysis().level_count()));
  if (c == 0 ||
      !sorted_entropies_[i].same_level_blocks_kept(n, threshold_at(c - 1), threshold_at(c)))
    frame(image).choose(n, threshold_at(c), chosen[static_cast<std::size_t>(n)]);
}

int SweepPipeline::candidates_considered(int image, int c, int n) {
  return static_cast<int>(frame(image).analysis().level_candidate_count(n, threshold_at(c)));
}

int SweepPipeline::undescribed(int image, int n) {
  const FrameAnalysis& analysis = frame(image).analysis();
  int count = 0;
  for (std::int32_t k : chosen_[static_cast<std::size_t>(image)][static_cast<std::size_t>(n)])
    count += analysis.described(n, k) ? 0 : 1;
  return count;
}

void SweepPipeline::describe_next(int image, int n, int count) {
  const FrameAnalysis& analysis = frame(image).analysis();
  to_describe_.clear();
  for (std::int32_t k : chosen_[static_cast<std::size_t>(image)][static_cast<std::size_t>(n)]) {
    if (static_cast<int>(to_describe_.size()) == count) break;
    if (!analysis.described(n, k)) to_describe_.push_back(k);
  }
  frame(image).describe(n, to_describe_);
}

// The features of one image at threshold c from its levels' selections, with the identity of
// each feature.
void SweepPipeline::finish_threshold(int image, int c) {
  const std::size_t i = static_cast<std::size_t>(image);
  std::vector<ThresholdFeatures>& features = image == 0 ? features_.a : features_.b;
  ThresholdFeatures& result = features[static_cast<std::size_t>(c)];
  result.repeat_of = -1;
  const FrameAnalysis& analysis = frame(image).analysis();
  const double threshold = threshold_at(c);
  result.ids.clear();
  for (int n = 0; n < analysis.level_count(); ++n)
    for (std::int32_t k : chosen_[i][static_cast<std::size_t>(n)])
      result.ids.push_back(id_offsets_[i][static_cast<std::size_t>(n)] + k);
  Features& out = result.features;
  analysis.assemble(chosen_[i], out);
  out.info.entropy_threshold_requested = threshold;
  out.info.entropy_threshold_used = threshold;
  out.info.threshold_lowered = false;
  out.info.image_entropy_bits = analysis.image_entropy_bits();
  out.info.blocks_total = analysis.blocks_total();
  out.info.blocks_kept = sorted_entropies_[i].blocks_kept(threshold);
}

int SweepPipeline::chosen_total(int image) const {
  std::size_t total = 0;
  for (const std::vector<std::int32_t>& level : chosen_[static_cast<std::size_t>(image)])
    total += level.size();
  return static_cast<int>(total);
}

void SweepPipeline::select_threshold(int image, int c) {
  if (selects_like_previous(image, c)) {
    repeat_previous(image, c);
    return;
  }
  const int levels = frame(image).analysis().level_count();
  for (int n = 0; n < levels; ++n) {
    choose_level(image, c, n);
    frame(image).describe(n, chosen_[static_cast<std::size_t>(image)][static_cast<std::size_t>(n)]);
  }
  finish_threshold(image, c);
}

const SweepFeatures& SweepPipeline::features(ImageView a, ImageView b, Repeats repeats) {
  // The two images are independent until matching: each is analysed by its frame pipeline (at
  // the sweep's lowest F), and later selected at every threshold, on its own thread.
  scheduler_.for_each(2, [&](int image) { analyse(image, image == 0 ? a : b); });
  const int cycles = begin_thresholds(repeats);
  // Selection and description share the memo of an analysis: serial per image, the two images
  // side by side.
  scheduler_.for_each(2, [&](int image) {
    for (int c = 0; c < cycles; ++c) select_threshold(image, c);
  });
  return features_;
}

bool SweepPipeline::mark_distinct(int c) {
  const std::size_t i = static_cast<std::size_t>(c);
  const auto same_as_previous = [&](const std::vector<ThresholdFeatures>& all) {
    const ThresholdFeatures& here = all[i].resolved(all);
    const ThresholdFeatures& before = all[i - 1].resolved(all);
    return &here == &before || same_features(here.features, before.features);
  };
  const bool same = c > 0 && same_as_previous(features_.a) && same_as_previous(features_.b);
  source_.resize(features_.a.size());
  if (c == 0) distinct_.clear();
  source_[i] = same ? source_[i - 1] : c;
  if (!same) distinct_.push_back(c);
  return !same;
}

void SweepPipeline::evaluate_in_order(int c) {
  if (!begin_evaluation(c)) return;
  matcher().offer_rows(matcher().rows_left());
  finish_matching(c);
  fit_threshold(c);
}

bool SweepPipeline::begin_evaluation(int c) {
  evaluated_.resize(features_.a.size());
  if (runs_.empty()) runs_.push_back({SweepMatcher(sweep_.match, *kernels_), {}, {}});
  if (c == 0) runs_[0].matcher.reset();
  if (!mark_distinct(c)) return false;
  const std::size_t i = static_cast<std::size_t>(c);
  const ThresholdFeatures& a = features_.a[i].resolved(features_.a);
  const ThresholdFeatures& b = features_.b[i].resolved(features_.b);
  runs_[0].matcher.begin(a.features.descriptors, a.ids, b.features.descriptors, b.ids);
  return true;
}

void SweepPipeline::finish_matching(int c) {
  evaluated_[static_cast<std::size_t>(c)].matches = runs_[0].matcher.finish();
}

int SweepPipeline::feature_count(int image, int c) const {
  const std::vector<ThresholdFeatures>& all = image == 0 ? features_.a : features_.b;
  return static_cast<int>(all[static_cast<std::size_t>(c)].resolved(all).ids.size());
}

void SweepPipeline::evaluate(MatchRun& run, std::size_t c) {
  const ThresholdFeatures& a = features_.a[c].resolved(features_.a);
  const ThresholdFeatures& b = features_.b[c].resolved(features_.b);
  evaluated_[c].matches =
      run.matcher.match(a.features.descriptors, a.ids, b.features.descriptors, b.ids);
  fit(run, c);
}

void SweepPipeline::fit(MatchRun& run, std::size_t c) {
  const ThresholdFeatures& a = features_.a[c].resolved(features_.a);
  const ThresholdFeatures& b = features_.b[c].resolved(features_.b);
  Evaluated& evaluated = evaluated_[c];
  homography_of(a.features, b.features, evaluated.matches, sweep_.ransac, run.src, run.dst,
                evaluated.homography);
}

// Estimated work of each distinct threshold matched first in a run (every distance) or after the
// one before it (the distances of the features new to it), in distances, plus a fixed part per
// threshold for RANSAC and the matcher's bookkeeping: about 80 distances per feature (leuven
// 1->2, thread CPU time per threshold: 1 M distances 2.6-2.9 ms, a threshold with almost no new
// feature 0.13-0.39 ms). With it, leuven's two runs take 8.1 and 6.5 ms instead of about 5-6
// and 9-12 ms for an even count of thresholds.
std::vector<int> SweepPipeline::cut_into_runs(int runs) {
  const int count = static_cast<int>(distinct_.size());
  std::vector<double> fresh(static_cast<std::size_t>(count)),
      incremental(static_cast<std::size_t>(count));
  const auto new_features = [&](const std::vector<ThresholdFeatures>& all,
                                std::vector<int>& new_counts) {
    const auto ids_at = [&](int k) -> const std::vector<std::int32_t>& {
      return all[static_cast<std::size_t>(distinct_[static_cast<std::size_t>(k)])]
          .resolved(all)
          .ids;
    };
    new_counts.assign(static_cast<std::size_t>(count), 0);
    std::int32_t max_id = -1;
    for (int k = 0; k < count; ++k)
      for (std::int32_t id : ids_at(k)) max_id = std::max(max_id, id);
    present_at_.assign(static_cast<std::size_t>(max_id) + 1,
                       -1);  // the last distinct threshold holding each id
    for (int k = 0; k < count; ++k) {
      for (std::int32_t id : ids_at(k)) {
        int& present = present_at_[static_cast<std::size_t>(id)];
        if (present != k - 1) ++new_counts[static_cast<std::size_t>(k)];
        present = k;
      }
    }
  };
  new_features(features_.a, new_a_);
  new_features(features_.b, new_b_);
  for (int k = 0; k < count; ++k) {
    const std::size_t c = static_cast<std::size_t>(distinct_[static_cast<std::size_t>(k)]);
    const double size_a = static_cast<double>(features_.a[c].resolved(features_.a).ids.size());
    const double size_b = static_cast<double>(features_.b[c].resolved(features_.b).ids.size());
    const double new_a = new_a_[static_cast<std::size_t>(k)],
                 new_b = new_b_[static_cast<std::size_t>(k)];
    const double fixed = 80.0 * (size_a + size_b) / 2;
    fresh[static_cast<std::size_t>(k)] = size_a * size_b + fixed;
    incremental[static_cast<std::size_t>(k)] = new_b * size_a + new_a * (size_b - new_b) + fixed;
  }
  return balanced_runs(fresh, incremental, runs);
}

void SweepPipeline::run(ImageView a, ImageView b, AdaptResult& result) {
  // Repeated thresholds are not copied: each one's features are those of the first of its run.
  features(a, b, Repeats::referenced);
  const int cycles = static_cast<int>(features_.a.size());
  // Low thresholds often keep every block: a threshold whose two feature sets equal the previous
  // one's has the same matches and model, so only the first of such a run is evaluated.
  for (int c = 0; c < cycles; ++c) mark_distinct(c);
  // Matching walks the distinct thresholds in order, each reusing the distances of the ones
  // before (SweepMatcher: match_descriptors' result, not a brute force per threshold), then fits
  // the threshold's model. With several threads the walk is cut into one run of consecutive
  // thresholds per thread, each with its own matcher (whose first threshold is matched in full),
  // cut where the estimated work is even: the same answers, each slot written by one run.
  evaluated_.resize(static_cast<std::size_t>(cycles));
  const std::vector<int>& distinct = distinct_;
  const int distinct_count = static_cast<int>(distinct.size());
  const int runs = std::min(scheduler_.concurrency(), distinct_count);
  while (static_cast<int>(runs_.size()) < runs)
    runs_.push_back({SweepMatcher(sweep_.match, *kernels_), {}, {}});
  const std::vector<int> run_begin =
      runs > 1 ? cut_into_runs(runs) : std::vector<int>{0, distinct_count};
  scheduler_.for_each(runs, [&](int r) {
    MatchRun& run = runs_[static_cast<std::size_t>(r)];
    run.matcher.reset();
    for (int k = run_begin[static_cast<std::size_t>(r)];
         k < run_begin[static_cast<std::size_t>(r) + 1]; ++k)
      evaluate(run, static_cast<std::size_t>(distinct[static_cast<std::size_t>(k)]));
  });
  choose(result);
}

void SweepPipeline::choose(AdaptResult& result) const {
  const std::vector<ThresholdFeatures>& features_a = features_.a;
  const std::vector<ThresholdFeatures>& features_b = features_.b;
  const auto at_a = [&](std::size_t c) -> const ThresholdFeatures& {
    return features_a[c].resolved(features_a);
  };
  const auto at_b = [&](std::size_t c) -> const ThresholdFeatures& {
    return features_b[c].resolved(features_b);
  };
  const std::vector<int>& source = source_;
  const int cycles = static_cast<int>(features_a.size());
  result.image_entropy_bits = features_.image_entropy_bits;
  result.curve.resize(static_cast<std::size_t>(cycles));
  result.chosen_index = -1;
  for (int c = 0; c < cycles; ++c) {
    const std::size_t i = static_cast<std::size_t>(c);
    const Evaluated& evaluated = evaluated_[static_cast<std::size_t>(source[i])];
    SweepPoint& point = result.curve[i];
    point.threshold = sweep_.first_threshold + sweep_.step * c;
    point.kept_blocks = features_a[i].features.info.blocks_kept;
    point.kept_blocks_b = features_b[i].features.info.blocks_kept;
    point.keypoints_a = static_cast<int>(at_a(i).features.keypoints.size());
    point.keypoints_b = static_cast<int>(at_b(i).features.keypoints.size());
    point.putative = static_cast<int>(evaluated.matches.size());
    point.inliers = evaluated.homography.found ? evaluated.homography.inliers : 0;
    point.cmr = point.putative > 0 ? static_cast<double>(point.inliers) / point.putative : 0.0;
    point.eligible = point.inliers >= sweep_.min_inliers;
    // Highest CMR among eligible thresholds; ties: more inliers, then the lower F (seen first).
    if (!point.eligible) continue;
    if (result.chosen_index >= 0) {
      const SweepPoint& best = result.curve[static_cast<std::size_t>(result.chosen_index)];
      if (point.cmr < best.cmr || (point.cmr == best.cmr && point.inliers <= best.inliers))
        continue;
    }
    result.chosen_index = c;
  }

  const std::size_t chosen =
      static_cast<std::size_t>(result.chosen_index >= 0 ? result.chosen_index : 0);
  result.found = result.chosen_index >= 0;
  result.threshold = result.curve[chosen].threshold;
  // The chosen threshold's features, wherever they are held, with its own info (thresholds);
  // copied, so the sweep's storage stays for the next pair.
  result.features_a = at_a(chosen).features;
  result.features_a.info = features_a[chosen].features.info;
  result.features_b = at_b(chosen).features;
  result.features_b.info = features_b[chosen].features.info;
  const Evaluated& evaluated = evaluated_[static_cast<std::size_t>(source[chosen])];
  result.matches = evaluated.matches;
  result.homography = evaluated.homography;
}

SweepFeatures sweep_features(ImageView a, ImageView b, const ExtractorOptions& options,
                             const SweepOptions& sweep, const KernelTable& kernels,
                             Repeats repeats) {
  SweepPipeline pipeline(options, sweep, kernels);
  return pipeline.features(a, b, repeats);
}

AdaptResult adapt_with_kernels(ImageView a, ImageView b, const ExtractorOptions& options,
                               const SweepOptions& sweep, const KernelTable& kernels) {
  SweepPipeline pipeline(options, sweep, kernels);
  AdaptResult result;
  pipeline.run(a, b, result);
  return result;
}

struct AdaptiveSweep::State {
  SweepPipeline pipeline;
};

AdaptiveSweep::AdaptiveSweep(const ExtractorOptions& options, const SweepOptions& sweep)
    : state_(std::make_unique<State>(
          State{SweepPipeline(options, sweep, kernel_table(options.kernels))})) {}

AdaptiveSweep::~AdaptiveSweep() = default;
AdaptiveSweep::AdaptiveSweep(AdaptiveSweep&&) noexcept = default;
AdaptiveSweep& AdaptiveSweep::operator=(AdaptiveSweep&&) noexcept = default;

AdaptResult AdaptiveSweep::run(ImageView a, ImageView b) {
  AdaptResult result;
  run(a, b, result);
  return result;
}

void AdaptiveSweep::run(ImageView a, ImageView b, AdaptResult& out) {
  state_->pipeline.run(a, b, out);
}

AdaptResult adapt(ImageView a, ImageView b, const ExtractorOptions& options,
                  const SweepOptions& sweep) {
  return AdaptiveSweep(options, sweep).run(a, b);
}

}  // namespace aief
