// aief.match, aief.find_homography and aief.adapt on numpy arrays.
#include <string>

#include <pybind11/stl.h>

#include "aief/adapt.hpp"
#include "aief/error.hpp"
#include "aief/homography.hpp"
#include "aief/match.hpp"
#include "python/bindings.hpp"
#include "python/option_keywords.hpp"
#include "python/py_extractor.hpp"

namespace aief::python {

namespace {

// N x 3 int32, a column per field of Match's list: query index, train index, Hamming distance.
py::array_t<std::int32_t> matches_array(const std::vector<Match>& matches) {
  constexpr auto columns = static_cast<py::ssize_t>(io::field_list_size<Match>());
  py::array_t<std::int32_t> out({static_cast<py::ssize_t>(matches.size()), columns});
  auto rows = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < matches.size(); ++i) {
    const auto r = static_cast<py::ssize_t>(i);
    py::ssize_t column = 0;
    io::for_each_field(matches[i], [&](std::string_view, int value) { rows(r, column++) = value; });
  }
  return out;
}

std::vector<Point2> points_from(const py::object& value, const char* name) {
  if (!py::isinstance<py::array>(value))
    throw Error(std::string(name) + " must be an N x 2 numpy array of points");
  const auto array = py::array_t<double, py::array::forcecast>::ensure(value);
  if (!array || array.ndim() != 2 || array.shape(1) != 2) {
    const auto given = py::reinterpret_borrow<py::array>(value);
    throw Error(std::string(name) + " must be an N x 2 array of (x, y), got " +
                (given.ndim() == 2
                     ? std::to_string(given.shape(0)) + " x " + std::to_string(given.shape(1))
                     : std::to_string(given.ndim()) + " dimensions"));
  }
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

// The calls that take options: their leading parameters, then the rows of their structs
// (python/option_keywords.hpp), so keywords, positions and defaults are the tables'.
OptionCall match_call() {
  OptionCall call("match", {"a", "b"}, 2);
  call.add_group<MatchOptions>();
  return call;
}

OptionCall find_homography_call() {
  OptionCall call("find_homography", {"src", "dst"}, 2);
  call.add_group<RansacOptions>();
  return call;
}

// adapt's options: the sweep's (group 0), then its matcher's (group 1).
OptionCall adapt_call() {
  OptionCall call("adapt", {"image_a", "image_b", "extractor"}, 2);
  call.add_group<SweepOptions>();
  call.add_group<MatchOptions>();
  return call;
}

// The call's signature, then its text and keywords: a docstring; the signature kept for the stub
// test. "NAME(...)\n--\n\n" first is CPython's __text_signature__, so inspect.signature and
// help() show the rows' parameters rather than (*args, **kwargs).
std::string documented(const OptionCall& call, const std::string& text,
                       const std::string& keywords) {
  keep_signature(call);
  return call.signature() + "\n--\n\n" + text + "\n\nKeywords:\n" + keywords;
}

}  // namespace

void bind_matching(py::module_& m) {
  py::options signatures_from_the_rows;  // pybind11's own would say (*args, **kwargs)
  signatures_from_the_rows.disable_function_signatures();
  static const std::string match_doc =
      documented(match_call(),
                 "Hamming matches of descriptors a (N x 32 uint8, or Features) into b: "
                 "an M x 3 int32 array of (query, train, distance), sorted by query; "
                 "ratio goes with matcher='ratio', 'mutual_ratio' or 'guided', as in aief match; "
                 "matcher='guided' needs Features.",
                 keywords_doc<MatchOptions>());
  m.def(
      "match",
      [](const py::args& args, const py::kwargs& kwargs) {
        OptionCall call = match_call();
        call.read(args, kwargs);
        const MatchOptions options = call.options<MatchOptions>(0);
        if (py::isinstance<PyFeatures>(call.leading(0)) &&
            py::isinstance<PyFeatures>(call.leading(1)))
          require_same_descriptor(call.leading(0).cast<const PyFeatures&>().descriptor, "a",
                                  call.leading(1).cast<const PyFeatures&>().descriptor, "b");
        std::vector<Match> matches;
        if (options.kind == MatcherKind::guided) {  // the keypoints' positions too
          for (int i : {0, 1})
            if (!py::isinstance<PyFeatures>(call.leading(i)))
              throw Error(std::string(i == 0 ? "a" : "b") +
                          ": matcher='guided' needs aief.Features, not descriptors alone: "
                          "it matches by the keypoints' positions too");
          const Features fa = engine_features(call.leading(0)),
                         fb = engine_features(call.leading(1));
          py::gil_scoped_release no_gil;
          matches = match_features(fa, fb, options);
        } else {
          const std::vector<Descriptor> da = descriptors_from(call.leading(0), "a"),
                                        db = descriptors_from(call.leading(1), "b");
          py::gil_scoped_release no_gil;
          matches = match_descriptors(da, db, options);
        }
        return matches_array(matches);
      },
      match_doc.c_str());

  static const std::string find_homography_doc =
      documented(find_homography_call(),
                 "RANSAC homography src -> dst (N x 2 points each): "
                 "(H 3 x 3 float64, or None when there is no model, N uint8 inlier mask). "
                 "Fixed seed: the same input, the same answer.",
                 keywords_doc<RansacOptions>());
  m.def(
      "find_homography",
      [](const py::args& args, const py::kwargs& kwargs) {
        OptionCall call = find_homography_call();
        call.read(args, kwargs);
        const RansacOptions options = call.options<RansacOptions>(0);
        const std::vector<Point2> s = points_from(call.leading(0), "src"),
                                  d = points_from(call.leading(1), "dst");
        HomographyResult result;
        {
          py::gil_scoped_release no_gil;
          result = find_homography_ransac(s, d, options);
        }
        return homography_tuple(result, s.size());
      },
      find_homography_doc.c_str());

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
            for (const SweepPoint& p : r.curve) rows.append(record_dict(p));
            return rows;
          },
          "one dict per threshold tried: "
          "threshold, kept_blocks (a), kept_blocks_b, keypoints_a, keypoints_b, putative, "
          "inliers, cmr (inliers / putative), eligible")
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
          "(H 3 x 3 float64 or None, M uint8 inlier mask over matches), "
          "as find_homography() returns");

  static const std::string adapt_doc =
      documented(adapt_call(),
                 "The paper's sweep of F over a pair (images as for Extractor.extract), "
                 "with the extractor's options (default options when None): "
                 "the chosen threshold, the curve, features and matches at it.",
                 keywords_doc<SweepOptions>() + keywords_doc<MatchOptions>());
  m.def(
      "adapt",
      [](const py::args& args, const py::kwargs& kwargs) {
        OptionCall call = adapt_call();
        call.read(args, kwargs);
        SweepOptions sweep = call.options<SweepOptions>(0);
        sweep.match = call.options<MatchOptions>(1);
        const py::object extractor_object = call.leading(2);
        if (!extractor_object.is_none() && !py::isinstance<PyExtractor>(extractor_object))
          throw py::type_error("extractor must be an aief.Extractor (or None), got " +
                               py::type::of(extractor_object).attr("__name__").cast<std::string>());
        const ExtractorOptions options =
            extractor_object.is_none()
                ? ExtractorOptions{}
                : extractor_object.cast<const PyExtractor&>().sweep_options();
        const ImageInput a(call.leading(0), options.max_image_pixels),
            b(call.leading(1), options.max_image_pixels);
        AdaptResult result;
        {
          py::gil_scoped_release no_gil;
          GrayImage buffer_a, buffer_b;
          result = adapt(a.gray(buffer_a), b.gray(buffer_b), options, sweep);
        }
        return result;
      },
      adapt_doc.c_str());
}

}  // namespace aief::python
