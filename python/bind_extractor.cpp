// aief.Extractor: ExtractorOptions as keyword arguments (the option table's Python keywords,
// core/options/option_table.hpp), extract() with the GIL released, and the options back as a dict.
#include <optional>
#include <string>
#include <type_traits>
#include <variant>

#include <pybind11/stl.h>

#include "aief/error.hpp"
#include "aief/extractor.hpp"
#include "core/options/option_table.hpp"
#include "io/image_io.hpp"
#include "io/option_record.hpp"
#include "parallel/scheduler.hpp"
#include "python/bindings.hpp"
#include "python/extraction_rendezvous.hpp"
#include "python/option_keywords.hpp"
#include "python/py_extractor.hpp"

namespace aief::python {

namespace {

// Extractor(*args, **kwargs): the table's keywords, by position or name, or the record's keys
// (what Extractor.options holds); None means not given (the mode's value). Resolved by the
// table, as the CLI is.
OptionCall extractor_call() {
  OptionCall call("Extractor", {}, 0);
  call.add_group<ExtractorOptions>(/*record_keys=*/true);
  return call;
}

std::unique_ptr<PyExtractor> extractor_from(const py::args& args, const py::kwargs& kwargs) {
  OptionCall call = extractor_call();
  call.read(args, kwargs);
  std::vector<table::GivenOption> given = call.given<ExtractorOptions>(0);
  ExtractorOptions options = table::resolve_options(given);
  if (const std::string note = parallel::cap_threads(options.threads, "threads"); !note.empty())
    warn(note);
  return std::make_unique<PyExtractor>(options, std::move(given));
}

// The record of the options, as Python values ("inf" as float('inf')).
py::dict options_dict(const ExtractorOptions& options) {
  py::dict d;
  for (const auto& [key, value] : table::record_of(options)) {
    const std::string name(key);
    std::visit(
        [&](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, std::string_view>) {
            if (table::row(key).kind() == table::ValueKind::number)
              d[name.c_str()] = py::float_(std::stod(std::string(v)));
            else
              d[name.c_str()] = std::string(v);
          } else {
            d[name.c_str()] = v;
          }
        },
        value);
  }
  return d;
}

template <auto Member>
auto field(const py::object& self) {
  return features_of(self).*Member;
}

// The constructor's docstring: the call and every keyword with its default, from the table.
std::string extractor_doc() {
  const OptionCall call = extractor_call();
  keep_signature(call);
  return call.signature() +
         "\n\nORB features with the AIEF entropy mask: "
         "a mode sets its options first, the keywords given override them, "
         "and a keyword the mode cannot honour is refused (as aief's CLI does). "
         "None keeps the mode's value. "
         "The keys of Extractor.options are keywords too, "
         "so Extractor(**extractor.options) makes the same extractor. "
         "A wrong type raises TypeError, a wrong value aief.Error.\n\nKeywords:\n" +
         keywords_doc<ExtractorOptions>();
}

}  // namespace

void bind_extractor(py::module_& m) {
  py::class_<PyFeatures>(m, "Features", "Keypoints and descriptors of one image, as numpy arrays")
      .def_property_readonly("keypoints", field<&PyFeatures::keypoints>,
                             "N x 2 float32, (x, y) in level-0 pixels, pixel centres at integers")
      .def_property_readonly("size", field<&PyFeatures::size>,
                             "N float32, patch diameter at the keypoint's level, level-0 pixels")
      .def_property_readonly("angle", field<&PyFeatures::angle>,
                             "N float32, orientation in degrees, [0, 360)")
      .def_property_readonly("response", field<&PyFeatures::response>, "N float32, FAST score")
      .def_property_readonly("octave", field<&PyFeatures::octave>, "N int32, pyramid level")
      .def_property_readonly("descriptors", field<&PyFeatures::descriptors>,
                             "N x 32 uint8, 256-bit descriptors of the kind `descriptor` names")
      .def_property_readonly(
          "descriptor", [](const PyFeatures& f) { return std::string(to_string(f.descriptor)); },
          "which descriptor `descriptors` holds: "
          "'rbrief' or 'box' (the extractor's descriptor option); "
          "aief.match refuses two Features of different kinds")
      .def_property_readonly("info", field<&PyFeatures::info>,
                             "how the entropy mask went (threshold used, blocks kept)")
      .def_property_readonly("image_width", field<&PyFeatures::image_width>,
                             "width of the image the features come from, pixels")
      .def_property_readonly("image_height", field<&PyFeatures::image_height>,
                             "height of the image the features come from, pixels")
      .def(
          "__len__", [](const py::object& self) { return features_of(self).keypoints.shape(0); },
          "the number of keypoints N")
      .def(
          "__repr__",
          [](const py::object& self) {
            auto* instance = reinterpret_cast<py::detail::instance*>(self.ptr());
            if (!instance->get_value_and_holder().holder_constructed())
              return std::string("<aief.Features, holding nothing>");
            const PyFeatures& f = self.cast<const PyFeatures&>();
            return "<aief.Features " + std::to_string(f.keypoints.shape(0)) + " keypoints, " +
                   std::to_string(f.image_width) + "x" + std::to_string(f.image_height) + ">";
          },
          "keypoint count and image size");

  static const std::string doc = extractor_doc();
  py::class_<PyExtractor>(m, "Extractor", doc.c_str())
      .def(py::init(&extractor_from))
      .def("extract", &PyExtractor::extract, py::arg("image"), py::arg("mask") = py::none(),
           "Features of a 2-D uint8 gray image "
           "(any strides; not copied when its rows are contiguous) "
           "or an H x W x 3 BGR / H x W x 4 BGRA uint8 image "
           "(converted to gray as the aief CLI converts files). "
           "mask: None, or a 2-D uint8 / bool array of the image's height and width, "
           "non-zero where keypoints may be; "
           "it acts before the distribution, "
           "so the n_features budget is filled inside it (docs/opencv.md). "
           "The GIL is released meanwhile.")
      .def("describe", &PyExtractor::describe, py::arg("image"), py::arg("keypoints"),
           py::arg("octave") = py::none(), py::arg("size") = py::none(),
           py::arg("angle") = py::none(), py::arg("response") = py::none(),
           py::arg("keep_angles") = false,
           "Descriptors of given keypoints, computed as for detected ones: (features, kept). "
           "keypoints: aief Features "
           "(e.g. from extract(); describing them gives back their bytes) "
           "or an N x 2 array of (x, y) level-0 pixels, "
           "with optional per-keypoint octave (pyramid level, default 0), size (default 31), "
           "angle and response. "
           "The angle is recomputed (intensity centroid) unless keep_angles "
           "(then each is used as given, any finite number of degrees, "
           "as cv2.ORB.compute uses it; with an N x 2 array, keep_angles needs angle=). "
           "Keypoints closer than 19 pixels to their level's edge are removed; "
           "kept: int32 indices of the kept keypoints in the given ones. "
           "An octave outside [0, levels), or not an integer, raises aief.Error.")
      .def_property_readonly(
          "options", [](const PyExtractor& e) { return options_dict(e.options()); },
          "every option in effect, as a dict (the mode's values filled in)")
      .def_property_readonly(
          "option_record", [](const PyExtractor& e) { return io::option_record_json(e.options()); },
          "the options as aief's output files record them (every field, one line of JSON): "
          "what the Dask recipe writes into its HDF5 groups")
      .def_property_readonly("kernel_name", &PyExtractor::kernel_name,
                             "the SIMD kernel set this extractor runs (e.g. avx2), "
                             "picked for this CPU or by `kernels`");
  m.def(
      "read_image",
      [](const py::object& path_given) {
        const std::string path = filesystem_path(path_given);
        GrayImage image;
        std::vector<std::string> warnings;
        {
          py::gil_scoped_release no_gil;
          image = io::read_gray_image(path, ExtractorOptions{}.max_image_pixels, &warnings);
        }
        for (const std::string& warning : warnings) warn(warning);
        py::array_t<std::uint8_t> out(
            {static_cast<py::ssize_t>(image.height()), static_cast<py::ssize_t>(image.width())});
        std::copy(image.data(),
                  image.data() + static_cast<std::size_t>(image.width()) * image.height(),
                  out.mutable_data());
        return out;
      },
      py::arg("path"),
      "An image file as the aief CLI reads it: "
      "2-D uint8 gray (colour by OpenCV's BGR2GRAY, 16-bit divided by 256); "
      "a UserWarning where the CLI warns (a JPEG cut short, its rest grey)");
  m.def(
      "option_changes",
      [](const std::optional<std::string>& record, const PyExtractor& extractor) {
        return io::option_changes(record, extractor.options());
      },
      py::arg("record"), py::arg("extractor"),
      "What an output whose option record is `record` (None: it has none) "
      "does not share with `extractor`'s options, "
      "as aief extract --batch reports it ('n_features 500 -> 3000'); "
      "empty when the extractor would write the same output, so a resume keeps it");
  m.def(
      "default_options", [] { return options_dict(ExtractorOptions{}); },
      "The C++ ExtractorOptions defaults, as a dict");
}

void bind_testing(py::module_& m) {
  m.def(
      "_option_table",
      [] {
        py::list rows;
        for (const table::OptionRow& row : table::rows()) {
          if (!row.has_front_ends()) continue;
          py::dict r;
          r["key"] = std::string(row.key);
          r["keyword"] = std::string(row.python_keyword);
          r["old_keyword"] = std::string(row.old_python_keyword);
          r["kind"] = std::string(row.kind() == table::ValueKind::integer  ? "integer"
                                  : row.kind() == table::ValueKind::number ? "number"
                                  : row.kind() == table::ValueKind::choice ? "choice"
                                                                           : "toggle");
          r["words"] = std::string(row.words);
          r["acts_with"] = std::string(row.acts_with);
          r["low"] = row.low;
          r["high"] = row.high;
          py::list names;
          if (row.field.choices)
            for (std::string_view name : row.field.choices()->names)
              names.append(std::string(name));
          r["names"] = names;
          rows.append(r);
        }
        return rows;
      },
      "Test hook: the option table's rows that have front ends (core/options/option_table.hpp)");
  m.def(
      "_signatures",
      [] {
        py::dict out;
        for (const auto& [function, signature] : kept_signatures())
          out[function.c_str()] = signature;
        return out;
      },
      "Test hook: each call that takes options, as its option rows write it (for the stub test)");
  m.def(
      "_record_fields",
      [] {
        py::dict out;
        out["ExtractionInfo"] = record_fields<ExtractionInfo>();
        out["SweepPoint"] = record_fields<SweepPoint>();
        return out;
      },
      "Test hook: each result record's keys and types, "
      "from its one field list (for the stub test)");
  m.def("_arm_extraction_rendezvous", &arm_extraction_rendezvous, py::arg("parties"),
        py::arg("timeout_s"),
        "Test hook: every extraction waits, GIL released, "
        "until `parties` are inside at once (0 disarms)");
  m.def(
      "_image_data_address",
      [](const py::object& image) {
        const ImageInput input(image);
        GrayImage buffer;
        return reinterpret_cast<std::uintptr_t>(input.gray(buffer).data);
      },
      "Test hook: the address of the gray pixels extract() would read "
      "(the array's own when not copied)");
}

}  // namespace aief::python
