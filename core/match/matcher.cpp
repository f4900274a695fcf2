#include "core/match/matcher.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "aief/error.hpp"
#include "core/kernels/kernel_table.hpp"
#include "core/match/band_nearest.hpp"
#include "core/match/guided_matcher.hpp"
#include "parallel/scheduler.hpp"

namespace aief {

namespace {

constexpr int kRowsPerBand = 64;  // queries per parallel piece; fixed, so merging is deterministic

}  // namespace

std::vector<Match> match_descriptors(const std::vector<Descriptor>& a,
                                     const std::vector<Descriptor>& b, const MatchOptions& options,
                                     const KernelTable& kernels) {
  options.validate();
  if (options.kind == MatcherKind::guided)
    throw Error(
        "matcher guided needs the keypoints' positions, not only descriptors: match the "
        "features (match_features, aief.match on Features, aief match)");
  std::vector<Match> matches;
  if (a.empty() || b.empty()) return matches;
  const int n_a = static_cast<int>(a.size()), n_b = static_cast<int>(b.size());
  const int bands = (n_a + kRowsPerBand - 1) / kRowsPerBand;

  std::vector<Nearest> row_nearest(static_cast<std::size_t>(n_a));
  // Column minima per band (only the mutual check needs them), merged in band order after.
  const bool mutual =
      options.kind == MatcherKind::mutual || options.kind == MatcherKind::mutual_ratio;
  std::vector<int> band_col_distance(mutual ? static_cast<std::size_t>(bands) * n_b : 0);
  std::vector<int> band_col_best(band_col_distance.size());
  const std::uint8_t* train = b.front().data();  // Descriptor is a plain byte array: contiguous

  // Each band writes its own rows and its own column minima: any schedule, the same matches.
  parallel::Scheduler().for_each(bands, [&](int band) {
    std::vector<std::uint16_t> distances(static_cast<std::size_t>(n_b));
    int* col_distance =
        mutual ? band_col_distance.data() + static_cast<std::ptrdiff_t>(band) * n_b : nullptr;
    int* col_best =
        mutual ? band_col_best.data() + static_cast<std::ptrdiff_t>(band) * n_b : nullptr;
    if (mutual) std::fill(col_distance, col_distance + n_b, std::numeric_limits<int>::max());
    const int end = std::min(n_a, (band + 1) * kRowsPerBand);
    for (int i = band * kRowsPerBand; i < end; ++i) {
      kernels.hamming_256_many(a[static_cast<std::size_t>(i)].data(), train, n_b, distances.data());
      Nearest nearest;
      for (int j = 0; j < n_b; ++j) {
        const int d = distances[static_cast<std::size_t>(j)];
        nearest.offer(d, j);
        if (mutual && d < col_distance[j]) {  // rows ascend: ties keep the lower query
          col_distance[j] = d;
          col_best[j] = i;
        }
      }
      row_nearest[static_cast<std::size_t>(i)] = nearest;
    }
  });

  const std::vector<int> col_best =
      mutual ? merge_band_column_minima(bands, n_b, band_col_distance, band_col_best)
             : std::vector<int>();

  int min_distance = std::numeric_limits<int>::max();
  for (const Nearest& nearest : row_nearest)
    min_distance = std::min(min_distance, nearest.best_distance);
  // The paper's filter (the ORB tutorial's "good matches"): max(2 * min_distance, 30).
  const int paper_limit = std::max(2 * min_distance, 30);

  for (int i = 0; i < n_a; ++i) {
    const Nearest& nearest = row_nearest[static_cast<std::size_t>(i)];
    if (nearest.best < 0 || nearest.best_distance > options.max_distance) continue;
    const bool is_mutual = mutual && col_best[static_cast<std::size_t>(nearest.best)] == i;
    const bool passes_ratio =
        static_cast<double>(nearest.best_distance) < options.ratio * nearest.second_distance;
    bool keep = false;
    switch (options.kind) {
      case MatcherKind::mutual: keep = is_mutual; break;
      case MatcherKind::ratio: keep = passes_ratio; break;
      case MatcherKind::paper: keep = nearest.best_distance <= paper_limit; break;
      case MatcherKind::mutual_ratio: keep = is_mutual && passes_ratio; break;
      case MatcherKind::guided: break;  // refused above
    }
    if (keep) matches.push_back({i, nearest.best, nearest.best_distance});
  }
  return matches;
}

std::vector<Match> match_descriptors(const std::vector<Descriptor>& a,
                                     const std::vector<Descriptor>& b,
                                     const MatchOptions& options) {
  return match_descriptors(a, b, options, kernel_table(KernelSet::auto_select));
}

std::vector<Match> match_features(const Features& a, const Features& b,
                                  const MatchOptions& options) {
  const KernelTable& kernels = kernel_table(KernelSet::auto_select);
  if (options.kind != MatcherKind::guided)
    return match_descriptors(a.descriptors, b.descriptors, options, kernels);
  options.validate();
  for (const Features* f : {&a, &b}) {
    if (f->keypoints.size() != f->descriptors.size())
      throw Error("matcher guided: features with " + std::to_string(f->keypoints.size()) +
                  " keypoints but " + std::to_string(f->descriptors.size()) + " descriptors");
    // A keypoint at infinity would lie on every epipolar line (inf <= inf) and void the matrix.
    for (std::size_t i = 0; i < f->keypoints.size(); ++i)
      if (!std::isfinite(f->keypoints[i].x) || !std::isfinite(f->keypoints[i].y))
        throw Error("matcher guided: keypoint " + std::to_string(i) + " of the " +
                    (f == &a ? "first" : "second") + " features is not at a finite position");
  }
  return match_guided(a, b, options, kernels);
}

void require_same_descriptor(DescriptorKind a, std::string_view what_a, DescriptorKind b,
                             std::string_view what_b) {
  if (a == b) return;
  throw Error(std::string(what_a) + " holds " + std::string(to_string(a)) + " descriptors, " +
              std::string(what_b) + " " + std::string(to_string(b)) +
              " descriptors: they cannot be matched (extract both with the same --descriptor)");
}

}  // namespace aief
