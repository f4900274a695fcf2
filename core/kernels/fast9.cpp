#include "core/kernels/fast9.hpp"

#include <algorithm>
#include <cassert>

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

void fast9_local_maxima_bits_scalar(const std::uint8_t* above, const std::uint8_t* row,
                                    const std::uint8_t* below, int x_begin, int x_end,
                                    int strong_threshold, std::uint64_t* maxima,
                                    std::uint64_t* strong) {
  const int words = fast9_maxima_words(x_end - x_begin);
  std::fill(maxima, maxima + words, std::uint64_t{0});
  std::fill(strong, strong + words, std::uint64_t{0});
  for (int x = x_begin; x < x_end; ++x) {
    const int s = row[x];
    if (s == 0) continue;
    if (s > row[x - 1] && s > row[x + 1] && s > above[x - 1] && s > above[x] && s > above[x + 1] &&
        s > below[x - 1] && s > below[x] && s > below[x + 1]) {
      const int i = x - x_begin;
      maxima[i / 64] |= std::uint64_t{1} << (i % 64);
      if (s >= strong_threshold) strong[i / 64] |= std::uint64_t{1} << (i % 64);
    }
  }
}

}  // namespace aief
