#include "core/kernels/fast9_local_maxima_bits.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "core/kernels/kernel_evidence.hpp"

namespace aief {

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

// The evidence (core/kernels/kernel_evidence.hpp): the validation case and the benchmark.

std::string check_fast9_local_maxima_bits(const KernelTable& scalar, const KernelTable& other,
                                          const GrayImage& src) {
  if (src.width() < 3 || src.height() < 3) return "";
  // Score-like rows: small values, many ties and zeros, so every comparison matters. Runs that
  // start at x = 1 and at odd offsets (the blocks of a level start anywhere), strong thresholds
  // below, inside and above the values.
  const int words = fast9_maxima_words(src.width());
  std::vector<std::uint64_t> a(2 * static_cast<std::size_t>(words)), b(a.size());
  for (int y = 1; y < src.height() - 1; ++y) {
    std::vector<std::uint8_t> rows[3];
    for (int k = 0; k < 3; ++k) {
      rows[k].resize(static_cast<std::size_t>(src.width()));
      for (int x = 0; x < src.width(); ++x)
        rows[k][static_cast<std::size_t>(x)] = src.data()[(y - 1 + k) * src.width() + x] >> 5;
    }
    for (int x_begin : {1, 2, 5}) {
      if (x_begin >= src.width() - 1) continue;
      for (int strong : {0, 3, 6, 300}) {
        std::fill(a.begin(), a.end(), ~std::uint64_t{0});  // every word must be written
        std::fill(b.begin(), b.end(), ~std::uint64_t{0});
        scalar.fast9_local_maxima_bits(rows[0].data(), rows[1].data(), rows[2].data(), x_begin,
                                       src.width() - 1, strong, a.data(), a.data() + words);
        other.fast9_local_maxima_bits(rows[0].data(), rows[1].data(), rows[2].data(), x_begin,
                                      src.width() - 1, strong, b.data(), b.data() + words);
        const std::string diff = first_difference(a, b, other.name, "word (maxima, then strong)");
        if (!diff.empty())
          return where(src, "row " + std::to_string(y) + " from x " + std::to_string(x_begin) +
                                " strong >= " + std::to_string(strong) + " " + diff);
      }
    }
  }
  return "";
}

// Every row of level 0's FAST scores, strong at 20.
KernelWorkload workload_fast9_local_maxima_bits(const KernelBenchInputs& in, const KernelTable& k) {
  const int width = static_cast<int>(in.scores[0].size());
  const int words = fast9_maxima_words(width - 2);
  return {[&in, &k, width, words,
           bits = std::vector<std::uint64_t>(
               2 * static_cast<std::size_t>(fast9_maxima_words(width)))]() mutable {
            for (std::size_t y = 1; y + 1 < in.scores.size(); ++y)
              k.fast9_local_maxima_bits(in.scores[y - 1].data(), in.scores[y].data(),
                                        in.scores[y + 1].data(), 1, width - 1, 20, bits.data(),
                                        bits.data() + words);
          },
          static_cast<long long>(in.scores.size() * in.scores[0].size())};
}

}  // namespace aief
