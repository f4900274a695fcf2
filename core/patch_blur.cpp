#include "core/patch_blur.hpp"

#include <algorithm>
#include <cassert>

#include "aief/options.hpp"

namespace aief {

namespace {

// Two patches' column spans closer than this are blurred as one span: a span's row setup, its
// 7 extra vertical columns and its overlapping last vector cost about as much as blurring the gap
// (callgrind on graf, AVX2, strips of 8 rows, blur + blur_patch_rows: 4.21 M instructions with
// gap 0, 3.96 M with 16, 3.88 M with 32, 3.92 M with 64, 4.08 M with 128).
constexpr int kSpanMergeGap = 32;

}  // namespace

void blur_patch_rows(const KernelTable& kernels, ImageView level, MutableImageView dst, int y_begin, int y_end,
                     const PixelPoint* points, int count, std::vector<int>& columns_scratch) {
  constexpr int r = kEdgeBorder;
  const int width = level.width;
  // [near_begin, near_end): the points within r rows of the strip, a window sliding down.
  int near_begin = 0, near_end = 0;
  for (int s0 = y_begin; s0 < y_end; s0 += kPatchBlurStripRows) {
    const int s1 = std::min(y_end, s0 + kPatchBlurStripRows);
    while (near_begin < count && points[near_begin].y < s0 - r) ++near_begin;
    near_end = std::max(near_end, near_begin);
    while (near_end < count && points[near_end].y <= s1 - 1 + r) ++near_end;
    if (near_begin == near_end) continue;
    std::vector<int>& xs = columns_scratch;
    xs.clear();
    for (int i = near_begin; i < near_end; ++i) xs.push_back(points[i].x);
    std::sort(xs.begin(), xs.end());
    const MutableImageView strip{dst.row(s0 - y_begin), dst.width, s1 - s0, dst.stride};
    int span_begin = std::max(0, xs.front() - r), span_end = std::min(width, xs.front() + r + 1);
    for (std::size_t i = 1; i < xs.size(); ++i) {
      const int begin = std::max(0, xs[i] - r), end = std::min(width, xs[i] + r + 1);
      if (begin > span_end + kSpanMergeGap) {
        kernels.gaussian7_rows(level, strip, s0, s1, span_begin, span_end);
        span_begin = begin;
      }
      span_end = std::max(span_end, end);
    }
    kernels.gaussian7_rows(level, strip, s0, s1, span_begin, span_end);
  }
}

}  // namespace aief
