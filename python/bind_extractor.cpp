// aief.Extractor: ExtractorOptions as keyword arguments (defaults read from the C++ struct),
// extract() with the GIL released, and the options back as a dict.
#include <algorithm>
#include <optional>
#include <string>

#include <pybind11/stl.h>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "io/image_io.hpp"
#include "python/bindings.hpp"
#include "python/extraction_rendezvous.hpp"
#include "python/py_extractor.hpp"

namespace aief::python {

PyFeatures PyExtractor::extract(const py::object& image) {
  const ImageInput input(image, extractor_.options().max_image_pixels);
  Features features;
  {
    py::gil_scoped_release no_gil;
    const std::lock_guard lock(mutex_);
    GrayImage buffer;
    const ImageView gray = input.gray(buffer);
    extraction_rendezvous();
    extractor_.extract(gray, features);
  }
  return to_python(features);
}

namespace {

// The CLI's order (tools/cli_args.cpp): entropy measure and kernels, then the mode's preset,
// then F; validate() is the one authority on ranges.
// The matching-quality options (docs/design.md §11) refine the mode; None keeps the mode's value.
struct QualityOverrides {
  py::object pool;  // a number >= 1, or "inf" / "off"
  std::optional<std::string> coordinates, starvation_guard, ranking;
  std::optional<bool> subpixel, auto_skips_uniform_blocks, auto_requires_two_classes;
};

void apply(const QualityOverrides& q, ExtractorOptions& options) {
  if (!q.pool.is_none()) {
    if (py::isinstance<py::str>(q.pool))
      options.candidate_pool = parse_candidate_pool(q.pool.cast<std::string>());
    else if (!py::isinstance<py::bool_>(q.pool) && (py::isinstance<py::float_>(q.pool) || py::isinstance<py::int_>(q.pool)))
      options.candidate_pool = q.pool.cast<double>();
    else
      throw Error("pool must be a number >= 1 or \"inf\", got " + std::string(py::repr(q.pool)));
  }
  if (q.coordinates) options.coordinates = parse_coordinate_map(*q.coordinates);
  if (q.starvation_guard) options.starvation_guard = parse_starvation_guard(*q.starvation_guard);
  if (q.subpixel) options.subpixel = *q.subpixel;
  if (q.auto_skips_uniform_blocks) options.auto_skips_uniform_blocks = *q.auto_skips_uniform_blocks;
  if (q.ranking) options.candidate_ranking = parse_candidate_ranking(*q.ranking);
  if (q.auto_requires_two_classes) options.auto_requires_two_classes = *q.auto_requires_two_classes;
}

ExtractorOptions options_from(int n_features, const std::string& mode, const py::object& threshold, int levels, double scale,
                              int threads, const std::string& kernels, int fast_threshold, int fast_min_threshold,
                              int block_size, const std::optional<std::string>& entropy, long long max_image_pixels,
                              const QualityOverrides& quality) {
  ExtractorOptions options;
  options.n_features = n_features;
  options.n_levels = levels;
  options.scale_factor = scale;
  options.threads = threads;
  options.kernels = parse_kernel_set(kernels);
  options.fast_threshold = fast_threshold;
  options.fast_min_threshold = fast_min_threshold;
  options.block_size = block_size;
  options.max_image_pixels = max_image_pixels;
  if (entropy) options.entropy = parse_entropy_measure(*entropy);
  options = options_for_mode(parse_mode(mode), options);
  apply(quality, options);
  if (py::isinstance<py::str>(threshold)) {
    const std::string text = threshold.cast<std::string>();
    if (text != "auto") throw Error("threshold must be a number of bits or \"auto\", got \"" + text + "\"");
    options.auto_threshold = true;
  } else if (py::isinstance<py::bool_>(threshold) || !(py::isinstance<py::float_>(threshold) || py::isinstance<py::int_>(threshold))) {
    throw Error("threshold must be a number of bits or \"auto\", got " + std::string(py::repr(threshold)));
  } else {
    options.entropy_threshold = threshold.cast<double>();
  }
  options.validate();
  return options;
}

py::dict options_dict(const ExtractorOptions& o) {
  py::dict d;
  d["n_features"] = o.n_features;
  d["scale_factor"] = o.scale_factor;
  d["n_levels"] = o.n_levels;
  d["fast_threshold"] = o.fast_threshold;
  d["fast_min_threshold"] = o.fast_min_threshold;
  d["block_size"] = o.block_size;
  d["distribution"] = std::string(to_string(o.distribution));
  d["entropy"] = std::string(to_string(o.entropy));
  d["entropy_threshold"] = o.entropy_threshold;
  d["auto_threshold"] = o.auto_threshold;
  d["coordinates"] = std::string(to_string(o.coordinates));
  d["subpixel"] = o.subpixel;
  d["candidate_pool"] = o.candidate_pool;
  d["starvation_guard"] = std::string(to_string(o.starvation_guard));
  d["auto_skips_uniform_blocks"] = o.auto_skips_uniform_blocks;
  d["candidate_ranking"] = std::string(to_string(o.candidate_ranking));
  d["auto_requires_two_classes"] = o.auto_requires_two_classes;
  d["kernels"] = std::string(to_string(o.kernels));
  d["threads"] = o.threads;
  d["max_image_pixels"] = o.max_image_pixels;
  return d;
}

}  // namespace

void bind_extractor(py::module_& m) {
  py::class_<PyFeatures>(m, "Features", "Keypoints and descriptors of one image, as numpy arrays")
      .def_readonly("keypoints", &PyFeatures::keypoints, "N x 2 float32, (x, y) in level-0 pixels, pixel centres at integers")
      .def_readonly("size", &PyFeatures::size, "N float32, patch diameter at the keypoint's level, level-0 pixels")
      .def_readonly("angle", &PyFeatures::angle, "N float32, orientation in degrees, [0, 360)")
      .def_readonly("response", &PyFeatures::response, "N float32, FAST score")
      .def_readonly("octave", &PyFeatures::octave, "N int32, pyramid level")
      .def_readonly("descriptors", &PyFeatures::descriptors, "N x 32 uint8, rBRIEF-256")
      .def_readonly("info", &PyFeatures::info, "how the entropy mask went (threshold used, blocks kept)")
      .def_readonly("image_width", &PyFeatures::image_width, "width of the image the features come from, pixels")
      .def_readonly("image_height", &PyFeatures::image_height, "height of the image the features come from, pixels")
      .def("__len__", [](const PyFeatures& f) { return f.keypoints.shape(0); }, "the number of keypoints N")
      .def("__repr__", [](const PyFeatures& f) {
        return "<aief.Features " + std::to_string(f.keypoints.shape(0)) + " keypoints, " + std::to_string(f.image_width) + "x" +
               std::to_string(f.image_height) + ">";
      }, "keypoint count and image size");

  const ExtractorOptions d;
  py::class_<PyExtractor>(m, "Extractor",
                          "ORB features with the AIEF entropy mask. Defaults are the C++ ExtractorOptions'; "
                          "pool, coordinates, subpixel, starvation_guard, auto_skips_uniform_blocks, ranking and "
                          "auto_requires_two_classes left None "
                          "keep the mode's values (as the CLI's flags). Invalid values raise aief.Error.")
      .def(py::init([](int n_features, const std::string& mode, const py::object& threshold, int levels, double scale,
                       int threads, const std::string& kernels, int fast_threshold, int fast_min_threshold, int block_size,
                       const std::optional<std::string>& entropy, long long max_image_pixels, const py::object& pool,
                       const std::optional<std::string>& coordinates, const std::optional<bool>& subpixel,
                       const std::optional<std::string>& starvation_guard, const std::optional<bool>& auto_skips_uniform_blocks,
                       const std::optional<std::string>& ranking, const std::optional<bool>& auto_requires_two_classes) {
             const QualityOverrides quality{pool,     coordinates, starvation_guard,         ranking,
                                            subpixel, auto_skips_uniform_blocks, auto_requires_two_classes};
             return std::make_unique<PyExtractor>(options_from(n_features, mode, threshold, levels, scale, threads, kernels,
                                                               fast_threshold, fast_min_threshold, block_size, entropy,
                                                               max_image_pixels, quality));
           }),
           py::arg("n_features") = d.n_features, py::arg("mode") = std::string(to_string(Mode::aief)),
           py::arg("threshold") = py::float_(d.entropy_threshold), py::arg("levels") = d.n_levels,
           py::arg("scale") = d.scale_factor, py::arg("threads") = d.threads,
           py::arg("kernels") = std::string(to_string(d.kernels)), py::kw_only(),
           py::arg("fast_threshold") = d.fast_threshold, py::arg("fast_min_threshold") = d.fast_min_threshold,
           py::arg("block_size") = d.block_size, py::arg("entropy") = py::none(),
           py::arg("max_image_pixels") = d.max_image_pixels, py::arg("pool") = py::none(), py::arg("coordinates") = py::none(),
           py::arg("subpixel") = py::none(), py::arg("starvation_guard") = py::none(),
           py::arg("auto_skips_uniform_blocks") = py::none(), py::arg("ranking") = py::none(),
           py::arg("auto_requires_two_classes") = py::none())
      .def("extract", &PyExtractor::extract, py::arg("image"),
           "Features of a 2-D uint8 gray image (any strides; not copied when its rows are contiguous) or an "
           "H x W x 3 BGR / H x W x 4 BGRA uint8 image (converted to gray as the aief CLI converts files). "
           "The GIL is released meanwhile.")
      .def_property_readonly("options", [](const PyExtractor& e) { return options_dict(e.options()); },
                             "every option in effect, as a dict (the mode's values filled in)")
      .def_property_readonly("kernel_name", &PyExtractor::kernel_name,
                             "the SIMD kernel set this extractor runs (e.g. avx2), picked for this CPU or by `kernels`");
  m.def(
      "read_image",
      [](const std::string& path) {
        GrayImage image;
        {
          py::gil_scoped_release no_gil;
          image = io::read_gray_image(path);
        }
        py::array_t<std::uint8_t> out({static_cast<py::ssize_t>(image.height()), static_cast<py::ssize_t>(image.width())});
        std::copy(image.data(), image.data() + static_cast<std::size_t>(image.width()) * image.height(), out.mutable_data());
        return out;
      },
      py::arg("path"),
      "An image file as the aief CLI reads it: 2-D uint8 gray (colour by OpenCV's BGR2GRAY, 16-bit divided by 256)");
  m.def("default_options", [] { return options_dict(ExtractorOptions{}); }, "The C++ ExtractorOptions defaults, as a dict");
}

void bind_testing(py::module_& m) {
  m.def("_arm_extraction_rendezvous", &arm_extraction_rendezvous, py::arg("parties"), py::arg("timeout_s"),
        "Test hook: every extraction waits, GIL released, until `parties` are inside at once (0 disarms)");
  m.def("_image_data_address", [](const py::object& image) {
    const ImageInput input(image);
    GrayImage buffer;
    return reinterpret_cast<std::uintptr_t>(input.gray(buffer).data);
  }, "Test hook: the address of the gray pixels extract() would read (the array's own when not copied)");
}

}  // namespace aief::python
