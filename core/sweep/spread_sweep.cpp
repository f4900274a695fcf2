#include "core/sweep/spread_sweep.hpp"

#include <algorithm>

namespace aief {

namespace {

// Estimated work of each piece, in AVX2 instructions: each piece's function summed over one
// sweep of the rendered baseline sequence at 640x480, 1000 features (callgrind, 140 M in all:
// matching rows 48 M, the two analyses about 30 M, descriptions 17 M and their blur 7 M, RANSAC
// 15 M, distribution 11 M; docs/speed.md), divided by what each piece reads. Only their ratios
// to the budget matter: they decide where a frame's share ends, never the answer.
constexpr double kEntropiesPerPixel = 5.5;  // pyramid level, histograms, entropy sums
constexpr double kDetectPerPixel = 8.5;     // FAST-9 over every non-flat block
// Distribution and raster order of a level, per candidate in its kept blocks and per level, by
// Distribution: the quadtree costs 2.5x the proportional distribution (28 M against 11.5 M).
constexpr double kChoosePerCandidate[] = {57, 140};
constexpr double kChoosePerLevel[] = {12000, 30000};
// The descriptor's input made over a level: the whole-level 7x7 blur rBRIEF reads (the box
// descriptor's integral image, a running sum, costs less).
constexpr double kDescriptorInputPerPixel = 4;
constexpr double kDescribePerKeypoint = 4000;    // orientation and rBRIEF
constexpr double kAssemblePerFeature = 120;      // a threshold's features put together
constexpr double kBeginMatchingPerFeature = 50;  // lists carried, descriptors blocked
constexpr double kPerDistance = 17;              // a Hamming distance and its offers to the lists
constexpr double kFinishPerFeature = 150;        // the lists read, the rare recomputation
constexpr double kRansacFixed = 400000;
constexpr double kRansacPerMatch = 1300;
constexpr double kFixedPiece = 20000;  // sorting entropies, a repeat, the choice

// A plain extraction costs about this much per pixel of level 0 and per feature asked (docs/
// speed.md: 18.4 M at 640x480 and 28.5 M at 800x640 with 1000 features), and a frame may add
// this share of it for the sweep (3.1 M at 640x480): with the estimates' error, the worst frame
// stays below 1.3x a plain frame's median (docs/design.md §10), and a sweep takes 48-58
// frames at 640x480.
constexpr double kFramePerPixel = 49;
constexpr double kFramePerFeature = 3250;
constexpr double kFrameShare = 0.17;

double pixels(int width, int height) { return static_cast<double>(width) * height; }

}  // namespace

SpreadSweep::SpreadSweep(const ExtractorOptions& options, const KernelTable& kernels)
    : sweep_(options, SweepOptions{}, kernels),
      distribution_(static_cast<std::size_t>(options.distribution)) {}

double SpreadSweep::frame_budget(ImageView image, int n_features) {
  return kFrameShare *
         (kFramePerPixel * pixels(image.width, image.height) + kFramePerFeature * n_features);
}

void SpreadSweep::start(ImageView a, ImageView b) {
  images_[0] = a;
  images_[1] = b;
  phase_ = Phase::entropies;
  image_ = level_ = c_ = thresholds_ = 0;
}

bool SpreadSweep::advance(double budget, AdaptResult& out) {
  last_work_ = 0;
  last_pieces_ = 0;
  done_ = false;
  while (phase_ != Phase::idle) {
    const double work = run_piece(budget - last_work_, last_work_ == 0, out);
    if (work < 0) break;

    last_work_ += work;
    if (work > 0) ++last_pieces_;
  }
  return done_;
}

void SpreadSweep::next_level_or(Phase after) {
  if (++level_ < sweep_.level_count(image_)) {
    phase_ = Phase::choose;
  } else {
    phase_ = after;
  }
}

void SpreadSweep::next_image_or(Phase after) {
  if (image_ == 0)
    image_ = 1;
  else
    phase_ = after;
}

void SpreadSweep::next_threshold(AdaptResult& out) {
  image_ = 0;
  if (++c_ < thresholds_) {
    phase_ = Phase::select;
    return;
  }
  sweep_.choose(out);
  phase_ = Phase::idle;
  done_ = true;
}

double SpreadSweep::run_piece(double room, bool must, AdaptResult& out) {
  const auto fits = [&](double work) { return must || work <= room; };
  const auto level_pixels = [&] {
    return pixels(sweep_.level_width(image_, level_), sweep_.level_height(image_, level_));
  };
  // A piece over the current level's pixels, `per_pixel` each: step() when it fits.
  const auto level_piece = [&](double per_pixel, const auto& step) {
    const double work = per_pixel * level_pixels();
    if (!fits(work)) return -1.0;
    step();
    return work;
  };
  switch (phase_) {
    case Phase::idle: return -1;
    case Phase::entropies: {
      const double work =
          kEntropiesPerPixel *
          (level_ == 0 ? pixels(images_[image_].width, images_[image_].height) : level_pixels());
      if (!fits(work)) return -1;
      if (level_ == 0) sweep_.start_analysis(image_, images_[image_]);
      sweep_.level_entropies(image_, level_);
      phase_ = Phase::detect;
      return work;
    }
    case Phase::detect:
      return level_piece(kDetectPerPixel, [&] {
        sweep_.detect_level(image_, level_);
        phase_ = Phase::entropies;
        if (++level_ == sweep_.level_count(image_)) {
          level_ = 0;
          next_image_or(Phase::begin_thresholds);
        }
      });
    case Phase::begin_thresholds: {
      if (!fits(kFixedPiece)) return -1;
      thresholds_ = sweep_.begin_thresholds(Repeats::referenced);
      c_ = 0;
      image_ = 0;
      phase_ = Phase::select;
      return kFixedPiece;
    }
    case Phase::select: {
      if (!sweep_.selects_like_previous(image_, c_)) {
        level_ = 0;
        phase_ = Phase::choose;
        return 0;
      }
      if (!fits(kFixedPiece)) return -1;
      sweep_.repeat_previous(image_, c_);
      next_image_or(Phase::begin_evaluation);
      return kFixedPiece;
    }
    case Phase::choose: {
      const double work =
          kChoosePerLevel[distribution_] +
          kChoosePerCandidate[distribution_] * sweep_.candidates_considered(image_, c_, level_);
      if (!fits(work)) return -1;
      sweep_.choose_level(image_, c_, level_);
      if (sweep_.undescribed(image_, level_) > 0)
        phase_ = sweep_.descriptor_input_ready(image_, level_) ? Phase::describe
                                                               : Phase::descriptor_input;
      else
        next_level_or(Phase::finish_threshold);
      return work;
    }
    case Phase::descriptor_input:
      return level_piece(kDescriptorInputPerPixel, [&] {
        sweep_.prepare_descriptor_input(image_, level_);
        phase_ = Phase::describe;
      });
    case Phase::describe: {
      const int left = sweep_.undescribed(image_, level_);
      int count = std::min(left, static_cast<int>(room / kDescribePerKeypoint));
      if (count <= 0) {
        if (!must) return -1;
        count = 1;
      }
      sweep_.describe_next(image_, level_, count);
      if (count == left) next_level_or(Phase::finish_threshold);
      return kDescribePerKeypoint * count;
    }
    case Phase::finish_threshold: {
      const double work = kFixedPiece + kAssemblePerFeature * sweep_.chosen_total(image_);
      if (!fits(work)) return -1;
      sweep_.finish_threshold(image_, c_);
      if (image_ == 0) {
        image_ = 1;
        phase_ = Phase::select;
      } else {
        phase_ = Phase::begin_evaluation;
      }
      return work;
    }
    case Phase::begin_evaluation: {
      const double work = kFixedPiece + kBeginMatchingPerFeature * (sweep_.feature_count(0, c_) +
                                                                    sweep_.feature_count(1, c_));
      if (!fits(work)) return -1;
      if (sweep_.begin_evaluation(c_))
        phase_ = Phase::rows;
      else
        next_threshold(out);
      return work;
    }
    case Phase::rows: {
      SweepMatcher& matcher = sweep_.matcher();
      double work = 0;
      while (matcher.rows_left() > 0) {
        const double row = kPerDistance * matcher.next_row_length();
        if (!(must && work == 0) && work + row > room) break;
        matcher.offer_rows(1);
        work += row;
      }
      if (matcher.rows_left() == 0) phase_ = Phase::finish_matching;
      return work > 0 ? work : phase_ == Phase::rows ? -1 : 0;
    }
    case Phase::finish_matching: {
      const double work = kFixedPiece + kFinishPerFeature * sweep_.feature_count(0, c_);
      if (!fits(work)) return -1;
      sweep_.finish_matching(c_);
      phase_ = Phase::fit;
      return work;
    }
    case Phase::fit: {
      const double work = kRansacFixed + kRansacPerMatch * sweep_.putative_matches(c_);
      if (!fits(work)) return -1;
      sweep_.fit_threshold(c_);
      next_threshold(out);
      return work;
    }
  }
  return -1;
}

}  // namespace aief
