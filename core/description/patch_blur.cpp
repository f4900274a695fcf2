#include "core/description/patch_blur.hpp"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cstdint>

#include "aief/options.hpp"
#include "core/kernels/rbrief_describe.hpp"

namespace aief {

namespace {

// Two patches' column spans closer than this are blurred as one span: a span's set-up, its 7
// extra vertical columns and its overlapping last vector cost about as much as blurring the gap
// (callgrind on graf, AVX2, strips of 8 rows, the patch blur stage: 2.89 M instructions with gap
// 24, 2.82 M with 32, 2.77 M with 48, 2.78 M with 64, 2.83 M with 96).
constexpr int kSpanMergeGap = 48;

// Sets bits [begin, end) of a bit row, 0 < end - begin <= 64: two words at most, no loop.
void mark_columns(std::uint64_t* bits, int begin, int end) {
  const std::uint64_t run = ~std::uint64_t{0} >> (64 - (end - begin));
  const int offset = begin & 63;
  bits[begin >> 6] |= run << offset;
  bits[(begin >> 6) + 1] |= (run >> 1) >> (63 - offset);  // the bits shifted past the word
}

// The first bit at or after `from` that is set in bits ^ flip (flip 0: a set bit, all ones: a
// clear one), or -1 if none is within `words` words.
int next_bit(const std::uint64_t* bits, int from, int words, std::uint64_t flip) {
  int word = from >> 6;
  if (word >= words) return -1;
  std::uint64_t w = (bits[word] ^ flip) & (~std::uint64_t{0} << (from & 63));
  while (w == 0) {
    if (++word == words) return -1;
    w = bits[word] ^ flip;
  }
  return word * 64 + std::countr_zero(w);
}

}  // namespace

void blur_patch_rows(const KernelTable& kernels, ImageView level, MutableImageView dst, int y_begin,
                     int y_end, const PixelPoint* points, int count,
                     std::vector<std::uint64_t>& columns_scratch) {
  constexpr int r = kSampleReach;
  const int width = level.width;
  // One bit per column: a point marks its patch's columns; runs of set bits closer than
  // kSpanMergeGap are blurred as one span. No sort, and a zero word at the end stops every run.
  const int words = width / 64 + 2;
  std::vector<std::uint64_t>& bits = columns_scratch;
  bits.assign(static_cast<std::size_t>(words), 0);
  // [near_begin, near_end): the points within r rows of the strip, a window sliding down.
  int near_begin = 0, near_end = 0;
  for (int s0 = y_begin; s0 < y_end; s0 += kPatchBlurStripRows) {
    const int s1 = std::min(y_end, s0 + kPatchBlurStripRows);
    while (near_begin < count && points[near_begin].y < s0 - r) ++near_begin;
    near_end = std::max(near_end, near_begin);
    while (near_end < count && points[near_end].y <= s1 - 1 + r) ++near_end;
    if (near_begin == near_end) continue;
    for (int i = near_begin; i < near_end; ++i) {
      // The strip's row nearest the point is the widest row of its sample disc there.
      const int y = points[i].y;
      const int rows_away = y < s0 ? s0 - y : (y >= s1 ? y - (s1 - 1) : 0);
      const int half_width = kSampleHalfWidth[rows_away];
      mark_columns(bits.data(), std::max(0, points[i].x - half_width),
                   std::min(width, points[i].x + half_width + 1));
    }
    const MutableImageView strip{dst.row(s0 - y_begin), dst.width, s1 - s0, dst.stride};
    constexpr std::uint64_t kSet = 0, kClear = ~std::uint64_t{0};
    for (int x = next_bit(bits.data(), 0, words, kSet); x >= 0;) {
      int end = next_bit(bits.data(), x, words, kClear), next;
      while ((next = next_bit(bits.data(), end, words, kSet)) >= 0 && next - end <= kSpanMergeGap)
        end = next_bit(bits.data(), next, words, kClear);
      kernels.gaussian7_rows(level, strip, s0, s1, x, end);
      x = next;
    }
    std::fill(bits.begin(), bits.end(), 0);
  }
}

}  // namespace aief
