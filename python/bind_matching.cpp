// aief.match, aief.find_homography and aief.adapt on numpy arrays.
#include <optional>
#include <sstream>
#include <string>

#include <pybind11/stl.h>

#include "aief/adapt.hpp"
#include "aief/error.hpp"
#include "aief/homography.hpp"
#include "aief/match.hpp"
#include "core/matcher.hpp"
#include "python/bindings.hpp"
#include "python/py_extractor.hpp"

namespace aief::python {

namespace {

// N x 3 int32: query index, train index, Hamming distance.
py::array_t<std::int32_t> matches_array(const std::vector<Match>& matches) {
  py::array_t<std::int32_t> out({static_cast<py::ssize_t>(matches.size()), py::ssize_t{3}});
  auto rows = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < matches.size(); ++i) {
    const auto r = static_cast<py::ssize_t>(i);
    rows(r, 0) = matches[i].query;
    rows(r, 1) = matches[i].train;
    rows(r, 2) = matches[i].distance;
  }
  return out;
}

std::vector<Point2> points_from(const py::object& value, const char* name) {
  if (!py::isinstance<py::array>(value))
    throw Error(std::string(name) + " must be an N x 2 numpy array of points");
  const auto array = py::array_t<double, py::array::forcecast>::ensure(value);
  if (!array || array.ndim() != 2 || array.shape(1) != 2)
    throw Error(std::string(name) + " must be an N x 2 array of (x, y), got " +
                std::to_string(py::reinterpret_borrow<py::array>(value).ndim()) + " dimensions");
  const auto rows = array.unchecked<2>();
  std::vector<Point2> points(static_cast<std::size_t>(array.shape(0)));
  for (py::ssize_t i = 0; i < array.shape(0); ++i)
    points[static_cast<std::size_t>(i)] = {rows(i, 0), rows(i, 1)};
  return points;
}

// (H as 3 x 3 float64 or None, inlier mask as N uint8), as cv2.findHomography returns.
py::tuple homography_tuple(const HomographyResult& result, std::size_t n) {
  py::array_t<std::uint8_t> mask(static_cast<py::ssize_t>(n));
  std::uint8_t* m = mask.mutable_data();
  for (std::size_t i = 0; i < n; ++i)
    m[i] = result.found && i < result.inlier_mask.size() ? result.inlier_mask[i] : 0;
  if (!result.found) return py::make_tuple(py::none(), mask);
  py::array_t<double> H({py::ssize_t{3}, py::ssize_t{3}});
  std::copy(result.H.begin(), result.H.end(), H.mutable_data());
  return py::make_tuple(H, mask);
}

// The CLI's rule (core/matcher.hpp): ratio only with matcher="ratio".
MatchOptions match_options(const std::string& matcher, const std::optional<double>& ratio,
                           int max_distance) {
  MatchOptions options = match_options_given(matcher, ratio, "ratio", "matcher");
  options.max_distance = max_distance;
  options.validate();
  return options;
}

}  // namespace

void bind_matching(py::module_& m) {
  const MatchOptions md;
  std::ostringstream ratio_default;
  ratio_default << md.ratio;
  static const std::string match_doc =
      "Hamming matches of descriptors a (N x 32 uint8, or Features) into b: an M x 3 int32 array "
      "of (query, train, "
      "distance), sorted by query. matcher: mutual | ratio | paper; ratio (Lowe's, default " +
      ratio_default.str() + ") goes with matcher='ratio' only, as aief match --ratio.";
  m.def(
      "match",
      [](const py::object& a, const py::object& b, const std::string& matcher,
         const std::optional<double>& ratio, int max_distance) {
        const MatchOptions options = match_options(matcher, ratio, max_distance);
        const std::vector<Descriptor> da = descriptors_from(a, "a"), db = descriptors_from(b, "b");
        std::vector<Match> matches;
        {
          py::gil_scoped_release no_gil;
          matches = match_descriptors(da, db, options);
        }
        return matches_array(matches);
      },
      py::arg("a"), py::arg("b"), py::arg("matcher") = std::string(to_string(md.kind)),
      py::arg("ratio") = py::none(), py::arg("max_distance") = md.max_distance, match_doc.c_str());

  const RansacOptions rd;
  m.def(
      "find_homography",
      [](const py::object& src, const py::object& dst, double threshold_px, double confidence,
         int max_iterations, std::uint64_t seed) {
        RansacOptions options;
        options.threshold_px = threshold_px;
        options.confidence = confidence;
        options.max_iterations = max_iterations;
        options.seed = seed;
        options.validate();
        const std::vector<Point2> s = points_from(src, "src"), d = points_from(dst, "dst");
        HomographyResult result;
        {
          py::gil_scoped_release no_gil;
          result = find_homography_ransac(s, d, options);
        }
        return homography_tuple(result, s.size());
      },
      py::arg("src"), py::arg("dst"), py::arg("threshold_px") = rd.threshold_px,
      py::arg("confidence") = rd.confidence, py::arg("max_iterations") = rd.max_iterations,
      py::arg("seed") = rd.seed,
      "RANSAC homography src -> dst (N x 2 points each): (H 3 x 3 float64, or None when there is "
      "no model, "
      "N uint8 inlier mask). Fixed seed: the same input, the same answer.");

  py::class_<AdaptResult>(m, "AdaptResult", "The sweep of the entropy threshold F over a pair")
      .def_readonly("found", &AdaptResult::found, "some threshold had enough inliers")
      .def_readonly("threshold", &AdaptResult::threshold, "the chosen F, bits")
      .def_readonly("chosen_index", &AdaptResult::chosen_index, "its row in curve, -1 when none")
      .def_readonly(
          "image_entropy_bits", &AdaptResult::image_entropy_bits,
          "E, the entropy of image_a (level 0), bits: it sets the number of thresholds tried")
      .def_property_readonly(
          "curve",
          [](const AdaptResult& r) {
            py::list rows;
            for (const SweepPoint& p : r.curve) {
              py::dict row;
              row["threshold"] = p.threshold;
              row["kept_blocks"] = p.kept_blocks;
              row["kept_blocks_b"] = p.kept_blocks_b;
              row["keypoints_a"] = p.keypoints_a;
              row["keypoints_b"] = p.keypoints_b;
              row["putative"] = p.putative;
              row["inliers"] = p.inliers;
              row["cmr"] = p.cmr;
              row["eligible"] = p.eligible;
              rows.append(row);
            }
            return rows;
          },
          "one dict per threshold tried: threshold, kept_blocks (a), kept_blocks_b, keypoints_a, "
          "keypoints_b, putative, inliers, cmr (inliers / putative), eligible")
      .def_property_readonly(
          "features_a", [](const AdaptResult& r) { return to_python(r.features_a); },
          "Features of image_a at the chosen threshold")
      .def_property_readonly(
          "features_b", [](const AdaptResult& r) { return to_python(r.features_b); },
          "Features of image_b at the chosen threshold")
      .def_property_readonly(
          "matches", [](const AdaptResult& r) { return matches_array(r.matches); },
          "M x 3 int32 (query, train, distance) at the chosen threshold, as match() returns")
      .def_property_readonly(
          "homography",
          [](const AdaptResult& r) { return homography_tuple(r.homography, r.matches.size()); },
          "(H 3 x 3 float64 or None, M uint8 inlier mask over matches), as find_homography() "
          "returns");

  const SweepOptions sd;
  m.def(
      "adapt",
      [](const py::object& image_a, const py::object& image_b, const PyExtractor* extractor,
         double first_threshold, double step, int min_inliers, const std::string& matcher) {
        SweepOptions sweep;
        sweep.first_threshold = first_threshold;
        sweep.step = step;
        sweep.min_inliers = min_inliers;
        sweep.match.kind = parse_matcher_kind(matcher);
        sweep.validate();
        const ExtractorOptions options = extractor ? extractor->options() : ExtractorOptions{};
        const ImageInput a(image_a, options.max_image_pixels), b(image_b, options.max_image_pixels);
        AdaptResult result;
        {
          py::gil_scoped_release no_gil;
          GrayImage buffer_a, buffer_b;
          result = adapt(a.gray(buffer_a), b.gray(buffer_b), options, sweep);
        }
        return result;
      },
      py::arg("image_a"), py::arg("image_b"), py::arg("extractor") = py::none(),
      py::arg("first_threshold") = sd.first_threshold, py::arg("step") = sd.step,
      py::arg("min_inliers") = sd.min_inliers,
      py::arg("matcher") = std::string(to_string(sd.match.kind)),
      "The paper's sweep of F over a pair (images as for Extractor.extract), with the extractor's "
      "options "
      "(default options when None): the chosen threshold, the curve, features and matches at it.");
}

}  // namespace aief::python
