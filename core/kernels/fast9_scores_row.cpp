#include "core/kernels/fast9_scores_row.hpp"

#include <algorithm>
#include <cassert>
#include <string>
#include <vector>

#include "core/kernels/kernel_evidence.hpp"

namespace aief {

namespace {

// The OpenCV score of one pixel: max over the 16 arcs of 9 of the arc's weakest difference, in
// both directions, minus one. d[k] = p - ring[k] (positive: ring darker), repeated so arcs wrap.
int corner_score(const std::uint8_t* p, const std::ptrdiff_t offsets[16]) {
  const int centre = p[0];
  int d[25];
  for (int k = 0; k < 16; ++k) d[k] = centre - p[offsets[k]];
  for (int k = 16; k < 25; ++k) d[k] = d[k - 16];
  int darker = -256, brighter = -256;  // best arc minimum of d, and of -d
  for (int start = 0; start < 16; ++start) {
    int min_d = 256, min_neg = 256;
    for (int k = start; k < start + 9; ++k) {
      min_d = std::min(min_d, d[k]);
      min_neg = std::min(min_neg, -d[k]);
    }
    darker = std::max(darker, min_d);
    brighter = std::max(brighter, min_neg);
  }
  return std::max(darker, brighter) - 1;
}

}  // namespace

void fast9_scores_row_scalar(const std::uint8_t* center, std::ptrdiff_t stride, int x_begin,
                             int x_end, int min_threshold, std::uint8_t* scores) {
  assert(min_threshold >= 1);
  std::ptrdiff_t offsets[16];
  for (int k = 0; k < 16; ++k) offsets[k] = kFastRingDy[k] * stride + kFastRingDx[k];
  for (int x = x_begin; x < x_end; ++x) {
    const std::uint8_t* p = center + x;
    const int v = p[0];
    // Early rejection as OpenCV: a 9-arc always covers one of ring pixels 0/8 and one of 4/12
    // ... at threshold t a corner needs some of them beyond v +- t.
    const int hi = v + min_threshold, lo = v - min_threshold;
    const auto beyond = [&](int k) {
      const int r = p[offsets[k]];
      return (r > hi ? 1 : 0) | (r < lo ? 2 : 0);
    };
    int mask = beyond(0) | beyond(8);
    if (mask == 0) {
      scores[x] = 0;
      continue;
    }
    mask &= beyond(2) | beyond(10);
    mask &= beyond(4) | beyond(12);
    mask &= beyond(6) | beyond(14);
    if (mask == 0) {
      scores[x] = 0;
      continue;
    }
    const int score = corner_score(p, offsets);
    scores[x] = score >= min_threshold ? static_cast<std::uint8_t>(score) : 0;
  }
}

// The evidence (core/kernels/kernel_evidence.hpp): the validation case and the benchmark.

std::string check_fast9_scores_row(const KernelTable& scalar, const KernelTable& other,
                                   const GrayImage& src) {
  if (src.width() < 7 || src.height() < 7) return "";
  std::vector<std::uint8_t> a(static_cast<std::size_t>(src.width())), b(a.size());
  for (int t : {1, 7, 20}) {
    for (int y = 3; y < src.height() - 3; ++y) {
      std::fill(a.begin(), a.end(), 0);
      std::fill(b.begin(), b.end(), 0);
      const std::uint8_t* row = src.data() + y * src.width();
      scalar.fast9_scores_row(row, src.width(), 3, src.width() - 3, t, a.data());
      other.fast9_scores_row(row, src.width(), 3, src.width() - 3, t, b.data());
      const std::string diff = first_difference(a, b, other.name, "x");
      if (!diff.empty())
        return where(src, "t=" + std::to_string(t) + " row " + std::to_string(y) + " " + diff);
    }
  }
  // Runs that start and end anywhere, as the pipeline's blocks do: every x_begin from the first
  // legal column (3) over more than one 512-bit vector, each against the scalar run, on one row.
  const int y = src.height() / 2;
  const std::uint8_t* row = src.data() + y * src.width();
  for (int x_begin = 3; x_begin < std::min(src.width() - 3, 3 + 70); ++x_begin) {
    for (int x_end : {x_begin + 1, std::min(src.width() - 3, x_begin + 33), src.width() - 3}) {
      if (x_end <= x_begin) continue;
      std::fill(a.begin(), a.end(), 0);
      std::fill(b.begin(), b.end(), 0);
      scalar.fast9_scores_row(row, src.width(), x_begin, x_end, 7, a.data());
      other.fast9_scores_row(row, src.width(), x_begin, x_end, 7, b.data());
      const std::string diff = first_difference(a, b, other.name, "x");
      if (!diff.empty())
        return where(src, "row " + std::to_string(y) + " run [" + std::to_string(x_begin) + ", " +
                              std::to_string(x_end) + ") " + diff);
    }
  }
  return "";
}

// Every row of every level at t = 7.
KernelWorkload workload_fast9_scores_row(const KernelBenchInputs& in, const KernelTable& k) {
  return {[&in, &k,
           scores = std::vector<std::uint8_t>(
               static_cast<std::size_t>(in.levels[0].width()))]() mutable {
            for (const GrayImage& level : in.levels)
              for (int y = 3; y < level.height() - 3; ++y)
                k.fast9_scores_row(level.view().row(y), level.width(), 3, level.width() - 3, 7,
                                   scores.data());
          },
          in.pixels};
}

}  // namespace aief
