#include "core/entropy/block_entropy.hpp"

#include <cassert>
#include <cmath>
#include <cstring>
#include <mutex>
#include <vector>

namespace aief {

namespace {

// c * log2(c) in Q32 fixed point, rounded: the entropy sums are sums of these integers, so their
// order cannot change a bit. Error per term <= 2^-33, far below the 1e-6 the tests ask.
constexpr double kQ32 = 4294967296.0;

std::uint64_t c_log2_c_q32(std::uint64_t c) {
  if (c <= 1) return 0;
  const double v = static_cast<double>(c) * std::log2(static_cast<double>(c));
  return static_cast<std::uint64_t>(std::llround(v * kQ32));
}

// Table for the counts of ordinary blocks (up to 64 x 64 pixels); bigger counts are computed on
// the spot with the same formula.
constexpr std::size_t kTableSize = 4097;

const std::uint64_t* c_log2_c_table() {
  static const std::vector<std::uint64_t> table = [] {
    std::vector<std::uint64_t> t(kTableSize);
    for (std::size_t c = 0; c < kTableSize; ++c) t[c] = c_log2_c_q32(c);
    return t;
  }();
  return table.data();
}

std::uint64_t c_log2_c(std::uint64_t c, const std::uint64_t* table) {
  return c < kTableSize ? table[c] : c_log2_c_q32(c);
}

// The intensity measure sums c_k * (k log2 k) over 255 bins: up to n * 255 log2 255 * 2^32,
// which passes 2^64 from about 2 Mpx of bright pixels (a 4K frame read 29.8 bits before). 128
// bits hold it for any uint32 count. (GCC and Clang, the compilers the build supports.)
__extension__ using Uint128 = unsigned __int128;

// H = log2(n) - S / (n 2^32) with S = sum c log2 c in Q32.
double entropy_from_sums(std::uint64_t n, Uint128 sum_q32) {
  if (n == 0) return 0.0;
  const double h = std::log2(static_cast<double>(n)) -
                   static_cast<double>(sum_q32) / (static_cast<double>(n) * kQ32);
  return h > 0.0 ? h : 0.0;
}

}  // namespace

double histogram_entropy_bits(const std::uint32_t* hist) {
  std::uint64_t n = 0;
  for (int k = 0; k < 256; ++k) n += hist[k];
  return histogram_entropy_bits(hist, n);
}

double histogram_entropy_bits(const std::uint32_t* hist, std::uint64_t pixels) {
  const std::uint64_t* table = c_log2_c_table();
  std::uint64_t sum = 0;
  if (pixels < kTableSize) {
    // Every count is in the table (a block's histogram): a loop without branches.
    for (int k = 0; k < 256; ++k) sum += table[hist[k]];
  } else {
    for (int k = 0; k < 256; ++k) sum += c_log2_c(hist[k], table);
  }
  // One gray level: H = 0 exactly. The general form leaves the rounding of n log2 n in Q32, a
  // few 1e-10 bits above 0 when n is not a power of two (an edge block's area), which a mask at
  // F = 0 would keep.
  if (sum == c_log2_c(pixels, table)) return 0.0;
  return entropy_from_sums(pixels, sum);
}

double intensity_entropy_bits(const std::uint32_t* hist) {
  // p = f / S over pixels: H = log2(S) - (1/S) sum_pixels f log2 f = log2(S) - (1/S) sum_k c_k k
  // log2 k.
  const std::uint64_t* table = c_log2_c_table();
  std::uint64_t s = 0;
  Uint128 sum = 0;
  for (int k = 1; k < 256; ++k) {
    s += static_cast<std::uint64_t>(hist[k]) * static_cast<std::uint64_t>(k);
    sum += static_cast<Uint128>(hist[k]) * table[k];
  }
  return entropy_from_sums(s, sum);
}

double entropy_bits(const std::uint32_t* hist, EntropyMeasure measure) {
  assert(measure != EntropyMeasure::off);
  return measure == EntropyMeasure::intensity ? intensity_entropy_bits(hist)
                                              : histogram_entropy_bits(hist);
}

double entropy_bits(const std::uint32_t* hist, std::uint64_t pixels, EntropyMeasure measure) {
  assert(measure != EntropyMeasure::off);
  return measure == EntropyMeasure::intensity ? intensity_entropy_bits(hist)
                                              : histogram_entropy_bits(hist, pixels);
}

}  // namespace aief
