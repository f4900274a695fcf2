#include "simd/kernel_validation.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <sstream>

#include "aief/extractor.hpp"
#include "core/kernels/fast9_detect.hpp"
#include "core/kernels/kernel_table.hpp"
#include "simd/kernels.hpp"

namespace aief {

namespace {

std::string where(const GrayImage& image, const std::string& detail) {
  return std::to_string(image.width()) + "x" + std::to_string(image.height()) + " " + detail;
}

template <class T>
std::string first_difference(const std::vector<T>& reference, const std::vector<T>& other,
                             const char* set_name, const std::string& what) {
  const std::size_t n = std::min(reference.size(), other.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (reference[i] != other[i]) {
      std::ostringstream out;
      out << what << " [" << i << "]: scalar " << +reference[i] << ", " << set_name << " "
          << +other[i];
      return out.str();
    }
  }
  if (reference.size() != other.size())
    return what + ": scalar gives " + std::to_string(reference.size()) + " values, " + set_name +
           " " + std::to_string(other.size());
  return "";
}

GrayImage random_gray(int width, int height, std::uint32_t seed, bool smooth) {
  GrayImage image(width, height);
  std::mt19937 rng(seed);
  for (int i = 0; i < width * height; ++i) image.data()[i] = static_cast<std::uint8_t>(rng());
  if (smooth && width > 2 &&
      height > 2) {  // a cheap blur: corners of every strength, not just noise
    GrayImage copy = image;
    for (int y = 1; y < height - 1; ++y)
      for (int x = 1; x < width - 1; ++x) {
        int sum = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) sum += copy.data()[(y + dy) * width + x + dx];
        const int stretched = (sum / 9 - 128) * 3 + 128;  // contrast back up after the blur
        image.data()[y * width + x] = static_cast<std::uint8_t>(std::clamp(stretched, 0, 255));
      }
  }
  return image;
}

// "WxH at (x, y): scalar A, SET B" for the first pixel where two resized images differ, or "".
std::string first_difference_of_resized(const GrayImage& a, const GrayImage& b,
                                        const std::string& set_name) {
  const int w = a.width(), h = a.height();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (a.data()[y * w + x] != b.data()[y * w + x])
        return std::to_string(w) + "x" + std::to_string(h) + " at (" + std::to_string(x) + ", " +
               std::to_string(y) + "): scalar " + std::to_string(a.data()[y * w + x]) + ", " +
               set_name + " " + std::to_string(b.data()[y * w + x]);
  return "";
}

std::string check_resize_bilinear_rows(const KernelTable& scalar, const KernelTable& other,
                                       const GrayImage& src) {
  if (src.width() < 2 || src.height() < 2) return "";
  // Every pyramid ratio the options allow, from just above 1 to 4 (scale_factor is in (1, 4]).
  for (double ratio : {1.01, 1.2, 1.5, 2.0, 2.7, 4.0}) {
    const int w = std::max(1, static_cast<int>(std::lround(src.width() / ratio)));
    const int h = std::max(1, static_cast<int>(std::lround(src.height() / ratio)));
    const ResizePlan plan = make_resize_plan(src.width(), src.height(), w, h);
    GrayImage a(w, h), b(w, h);
    scalar.resize_bilinear_rows(src.view(), plan, a.mutable_view(), 0, h);
    other.resize_bilinear_rows(src.view(), plan, b.mutable_view(), 0, h);
    const std::string difference = first_difference_of_resized(a, b, other.name);
    if (!difference.empty())
      return where(src, "ratio " + std::to_string(ratio) + " -> " + difference);
  }
  return "";
}

std::string check_resize_opencv_linear_rows(const KernelTable& scalar, const KernelTable& other,
                                            const GrayImage& src) {
  // ORB-SLAM's pyramid ratio (cvRound of the size over 1.2), the options' range of ratios, an
  // exact halving, and upscaling (cv::resize's any ratio; no group fits past about 2x down).
  for (double ratio : {1.2, 1.01, 1.5, 2.0, 2.7, 4.0, 0.6}) {
    const int w = std::max(1, static_cast<int>(std::lround(src.width() / ratio)));
    const int h = std::max(1, static_cast<int>(std::lround(src.height() / ratio)));
    const OpenCvResizePlan plan = make_opencv_resize_plan(src.width(), src.height(), w, h);
    GrayImage a(w, h), b(w, h);
    scalar.resize_opencv_linear_rows(src.view(), plan, a.mutable_view(), 0, h);
    // The other kernel in two bands, the second starting on its own row buffers.
    other.resize_opencv_linear_rows(src.view(), plan, b.mutable_view(), 0, h / 2);
    other.resize_opencv_linear_rows(src.view(), plan, b.mutable_view(), h / 2, h);
    const std::string difference = first_difference_of_resized(a, b, other.name);
    if (!difference.empty())
      return where(src, "ratio " + std::to_string(ratio) + " -> " + difference);
  }
  return "";
}

std::string check_gaussian7_rows(const KernelTable& scalar, const KernelTable& other,
                                 const GrayImage& src) {
  if (src.width() < 4 || src.height() < 4) return "";
  GrayImage a(src.width(), src.height()), b(src.width(), src.height());
  scalar.gaussian7_rows(src.view(), a.mutable_view(), 0, src.height(), 0, src.width());
  // The other kernel in two bands, as the extractor streams it (dst row 0 is the band's first
  // row), and each band in column spans, as it blurs only the columns rBRIEF reads: a span at
  // either edge, a narrow one (scalar tail) and a wide one.
  const int cut = src.height() / 3;
  std::vector<int> column_cuts = {0, std::min(src.width(), 5), src.width() / 2, src.width()};
  column_cuts.erase(std::unique(column_cuts.begin(), column_cuts.end()), column_cuts.end());
  for (std::size_t i = 0; i + 1 < column_cuts.size(); ++i) {
    other.gaussian7_rows(src.view(), b.mutable_view(), 0, cut, column_cuts[i], column_cuts[i + 1]);
    other.gaussian7_rows(
        src.view(), {b.data() + cut * src.width(), src.width(), src.height() - cut, src.width()},
        cut, src.height(), column_cuts[i], column_cuts[i + 1]);
  }
  for (int y = 0; y < src.height(); ++y)
    for (int x = 0; x < src.width(); ++x)
      if (a.data()[y * src.width() + x] != b.data()[y * src.width() + x])
        return where(src, "at (" + std::to_string(x) + ", " + std::to_string(y) + "): scalar " +
                              std::to_string(a.data()[y * src.width() + x]) + ", " + other.name +
                              " " + std::to_string(b.data()[y * src.width() + x]));
  return "";
}

std::string check_accumulate_histogram(const KernelTable& scalar, const KernelTable& other,
                                       const GrayImage& src) {
  // The whole image and an inner rectangle with the full stride.
  for (int inset : {0, 1}) {
    const int w = src.width() - 2 * inset, h = src.height() - 2 * inset;
    if (w <= 0 || h <= 0) continue;
    std::vector<std::uint32_t> a(256, 3), b(256, 3);  // accumulate: start from the same counts
    const std::uint8_t* data = src.data() + inset * src.width() + inset;
    scalar.accumulate_histogram(data, src.width(), w, h, a.data());
    other.accumulate_histogram(data, src.width(), w, h, b.data());
    const std::string diff = first_difference(a, b, other.name, "bin");
    if (!diff.empty()) return where(src, "inset " + std::to_string(inset) + " " + diff);
  }
  return "";
}

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

std::vector<PixelPoint> inner_points(const GrayImage& src, int border, int step) {
  std::vector<PixelPoint> points;
  for (int y = border; y < src.height() - border; y += step)
    for (int x = border; x < src.width() - border; x += step) points.push_back({x, y});
  return points;
}

std::string check_ic_moments(const KernelTable& scalar, const KernelTable& other,
                             const GrayImage& src) {
  const std::vector<PixelPoint> points = inner_points(src, kPatchRadius, 3);
  if (points.empty()) return "";
  const int n = static_cast<int>(points.size());
  std::vector<std::int32_t> a10(points.size()), a01(points.size()), b10(points.size()),
      b01(points.size());
  scalar.ic_moments(src.view(), points.data(), n, a10.data(), a01.data());
  other.ic_moments(src.view(), points.data(), n, b10.data(), b01.data());
  std::string diff = first_difference(a10, b10, other.name, "m10 of point");
  if (diff.empty()) diff = first_difference(a01, b01, other.name, "m01 of point");
  return diff.empty() ? "" : where(src, diff);
}

std::string check_rbrief_describe(const KernelTable& scalar, const KernelTable& other,
                                  const GrayImage& src) {
  const std::vector<PixelPoint> points = inner_points(src, kEdgeBorder, 5);
  if (points.empty()) return "";
  std::vector<float> angles(points.size());
  for (std::size_t i = 0; i < angles.size(); ++i)
    angles[i] = static_cast<float>((i * 37) % 360) + 0.25f * static_cast<float>(i % 4);
  std::vector<std::uint8_t> a(points.size() * 32), b(a.size());
  scalar.rbrief_describe(src.view(), points.data(), angles.data(), static_cast<int>(points.size()),
                         a.data());
  other.rbrief_describe(src.view(), points.data(), angles.data(), static_cast<int>(points.size()),
                        b.data());
  const std::string diff = first_difference(a, b, other.name, "descriptor byte");
  return diff.empty() ? "" : where(src, diff);
}

std::string check_hamming_256_many(const KernelTable& scalar, const KernelTable& other,
                                   const GrayImage& src) {
  const int n = std::min(src.width() * src.height() / 32, 300);
  if (n < 1) return "";
  const std::uint8_t* train = src.data();
  std::vector<std::uint16_t> a(static_cast<std::size_t>(n)), b(a.size());
  for (int count : {n, std::max(0, n - 1), std::min(n, 1)}) {
    scalar.hamming_256_many(train, train, count, a.data());
    other.hamming_256_many(train, train, count, b.data());
    a.resize(static_cast<std::size_t>(count));
    b.resize(static_cast<std::size_t>(count));
    const std::string diff = first_difference(a, b, other.name, "distance");
    if (!diff.empty()) return where(src, diff);
    a.resize(static_cast<std::size_t>(n));
    b.resize(static_cast<std::size_t>(n));
  }
  return "";
}

// The image's bytes as descriptors, blocked; the query is each of the first few descriptors.
std::string check_hamming_256_blocked(const KernelTable& scalar, const KernelTable& other,
                                      const GrayImage& src) {
  const int n = std::min(src.width() * src.height() / 32, 300);
  if (n < 1) return "";
  std::vector<std::uint32_t> blocked;
  block_descriptors(src.data(), n, blocked);
  const int blocks = hamming_block_count(n);
  std::vector<std::uint16_t> a(static_cast<std::size_t>(blocks * kHammingBlock)), b(a.size());
  for (int query = 0; query < std::min(n, 5); ++query) {
    for (int count : {blocks, blocks - 1, 1}) {
      if (count < 1) continue;
      std::fill(a.begin(), a.end(), 0xffff);
      std::fill(b.begin(), b.end(), 0xffff);
      scalar.hamming_256_blocked(src.data() + 32 * query, blocked.data(), count, a.data());
      other.hamming_256_blocked(src.data() + 32 * query, blocked.data(), count, b.data());
      const std::string diff = first_difference(a, b, other.name, "distance to train");
      if (!diff.empty()) return where(src, "query " + std::to_string(query) + ", " + diff);
    }
  }
  return "";
}

// Distances and bounds made from the image's bytes: distances in 0..256 plus the excluded value
// 0x7fff, bounds in -1..256, at every query bound the matcher uses (-1 none, 256 all).
std::string check_positions_within_bounds(const KernelTable& scalar, const KernelTable& other,
                                          const GrayImage& src) {
  const int n = src.width() * src.height();
  if (n < 1) return "";
  std::vector<std::uint16_t> distances(static_cast<std::size_t>(n));
  std::vector<std::int16_t> bounds(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const int v = src.data()[k], u = src.data()[(k * 7 + 3) % n];
    distances[static_cast<std::size_t>(k)] =
        static_cast<std::uint16_t>(v == 255 ? 0x7fff : v + (u & 1));
    bounds[static_cast<std::size_t>(k)] = static_cast<std::int16_t>(u == 0     ? -1
                                                                    : u == 255 ? 256
                                                                               : u);
  }
  std::vector<std::int32_t> a(static_cast<std::size_t>(n)), b(a.size());
  for (int query_bound : {-1, 0, 60, 128, 200, 256}) {
    for (int count : {n, n - 1, std::min(n, 33)}) {
      a.resize(static_cast<std::size_t>(scalar.positions_within_bounds(
          distances.data(), bounds.data(), count, query_bound, a.data())));
      b.resize(static_cast<std::size_t>(other.positions_within_bounds(
          distances.data(), bounds.data(), count, query_bound, b.data())));
      const std::string diff = first_difference(a, b, other.name, "position within bounds");
      if (!diff.empty())
        return where(src, "query bound " + std::to_string(query_bound) + ", " + diff);
      a.resize(static_cast<std::size_t>(n));
      b.resize(static_cast<std::size_t>(n));
    }
  }
  return "";
}

std::string check_unsharp_row(const KernelTable& scalar, const KernelTable& other,
                              const GrayImage& src) {
  // Amounts over the whole range, 0 and the largest included, from a seed of the image's size.
  std::mt19937 rng(static_cast<std::uint32_t>(src.width() * 131 + src.height()));
  std::uniform_int_distribution<int> amount(0, kUnsharpMaxAmountQ8);
  const std::size_t width = static_cast<std::size_t>(src.width());
  std::vector<std::int16_t> amounts(width);
  std::vector<std::uint16_t> sums_a(width + 4), sums_b(width + 4);
  std::vector<std::uint8_t> a(width), b(width);
  for (int y = 0; y < src.height(); ++y) {
    for (std::int16_t& value : amounts) value = static_cast<std::int16_t>(amount(rng));
    amounts[0] = kUnsharpMaxAmountQ8;
    amounts[width - 1] = 0;
    scalar.unsharp_row(src.view(), y, amounts.data(), sums_a.data(), a.data());
    other.unsharp_row(src.view(), y, amounts.data(), sums_b.data(), b.data());
    const std::string diff = first_difference(a, b, other.name, "pixel");
    if (!diff.empty()) return where(src, "row " + std::to_string(y) + " " + diff);
  }
  return "";
}

std::string check_binomial5_row(const KernelTable& scalar, const KernelTable& other,
                               const GrayImage& src) {
  const std::size_t width = static_cast<std::size_t>(src.width());
  std::vector<std::uint16_t> sums_a(width + 4), sums_b(width + 4);
  std::vector<std::uint8_t> a(width), b(width);
  for (int y = 0; y < src.height(); ++y) {
    scalar.binomial5_row(src.view(), y, sums_a.data(), a.data());
    other.binomial5_row(src.view(), y, sums_b.data(), b.data());
    const std::string diff = first_difference(a, b, other.name, "pixel");
    if (!diff.empty()) return where(src, "row " + std::to_string(y) + " " + diff);
  }
  return "";
}

std::string check_extract(KernelSet set, const GrayImage& src) {
  if (src.width() < 2 * kEdgeBorder + 1 || src.height() < 2 * kEdgeBorder + 1) return "";
  // The default mode (sub-pixel, pool, per-level guard, automatic F) and the paper's conventions.
  for (Mode mode : {Mode::aief, Mode::aief_paper, Mode::orbslam2}) {
    ExtractorOptions reference_options = options_for_mode(mode);
    reference_options.auto_threshold = mode == Mode::aief;
    reference_options.kernels = KernelSet::scalar;
    reference_options.threads = 1;
    const Features reference = Extractor(reference_options).extract(src.view());
    for (int threads : {1, 2}) {
      ExtractorOptions options = reference_options;
      options.kernels = set;
      options.threads = threads;
      const Features other = Extractor(options).extract(src.view());
      const std::string label =
          std::string(to_string(mode)) + ", " + std::to_string(threads) + " thread(s): ";
      if (other.keypoints.size() != reference.keypoints.size())
        return where(src, label + std::to_string(reference.keypoints.size()) +
                              " keypoints with scalar, " + std::to_string(other.keypoints.size()));
      for (std::size_t i = 0; i < reference.keypoints.size(); ++i) {
        const Keypoint &r = reference.keypoints[i], &o = other.keypoints[i];
        if (std::memcmp(&r, &o, sizeof r) != 0 ||
            reference.descriptors[i] != other.descriptors[i]) {
          std::ostringstream out;
          out << label << "keypoint " << i << ": scalar (" << r.x << ", " << r.y << ", "
              << r.angle_deg << "), other (" << o.x << ", " << o.y << ", " << o.angle_deg << ")"
              << (reference.descriptors[i] != other.descriptors[i] ? ", descriptors differ" : "");
          return where(src, out.str());
        }
      }
      if (other.info.entropy_threshold_used != reference.info.entropy_threshold_used ||
          other.info.image_entropy_bits != reference.info.image_entropy_bits)
        return where(src, label + "entropy or threshold differs");
    }
  }
  return "";
}

// One check per kernel of the list (core/kernels/kernel_table.hpp), each named check_<kernel>: a kernel
// added to the list without a check here does not compile.
using KernelCheck = std::string (*)(const KernelTable& scalar, const KernelTable& other,
                                    const GrayImage& src);
struct NamedCheck {
  const char* kernel;
  KernelCheck check;
};
constexpr NamedCheck kKernelChecks[] = {
#define AIEF_KERNEL_CHECK(kernel) {#kernel, &check_##kernel},
    AIEF_FOR_EACH_KERNEL(AIEF_KERNEL_CHECK)
#undef AIEF_KERNEL_CHECK
};
constexpr const char* kWholePipeline = "extract";

}  // namespace

const std::vector<std::string>& validated_kernel_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const NamedCheck& entry : kKernelChecks) out.emplace_back(entry.kernel);
    out.emplace_back(kWholePipeline);
    return out;
  }();
  return names;
}

std::vector<GrayImage> validation_images() {
  std::vector<GrayImage> images;
  std::uint32_t seed = 1;
  std::vector<int> widths;
  for (int w = 1; w <= 70; ++w) widths.push_back(w);
  // Around the vector widths, and rows that end just past the blur's 512-pixel chunks.
  for (int w : {71, 72, 73, 127, 129, 255, 257, 513, 517, 541, 575, 577}) widths.push_back(w);
  for (int w : widths)
    for (int h : {1, 3, 37}) images.push_back(random_gray(w, h, seed++, (w + h) % 2 == 0));
  for (const auto& [w, h] :
       std::vector<std::pair<int, int>>{{64, 64}, {97, 61}, {131, 140}, {257, 129}, {333, 211}})
    images.push_back(random_gray(w, h, seed++, true));
  return images;
}

std::string validate_kernel(const std::string& kernel, KernelSet set,
                            const std::vector<GrayImage>& images) {
  const KernelTable& scalar = kernel_table(KernelSet::scalar);
  const KernelTable& other = kernel_table(set);
  KernelCheck check = nullptr;
  for (const NamedCheck& entry : kKernelChecks)
    if (kernel == entry.kernel) check = entry.check;
  if (check == nullptr && kernel != kWholePipeline) return "unknown kernel '" + kernel + "'";
  for (const GrayImage& image : images) {
    const std::string diff =
        check != nullptr ? check(scalar, other, image) : check_extract(set, image);
    if (!diff.empty()) return diff;
  }
  return "";
}

}  // namespace aief
