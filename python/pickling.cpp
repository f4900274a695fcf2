// Pickling of aief.Extractor, aief.Features and aief.AdaptResult, so that they go to and come
// back from worker processes (multiprocessing, concurrent.futures, Dask). Features pickle as
// their numpy arrays. Extractor and AdaptResult pickle as the engine's own structs in bytes,
// after a tag of the module version and the structs' sizes: a pickle of another build is refused
// with a clear error, never misread. An Extractor is rebuilt from its options (fresh buffers).
#include <cstring>
#include <type_traits>

#include "aief/adapt.hpp"
#include "aief/error.hpp"
#include "aief/version.hpp"
#include "core/options/option_table.hpp"
#include "python/bindings.hpp"
#include "python/py_extractor.hpp"

namespace aief::python {

namespace {

// The build a state comes from: the version and the layout of every struct written as bytes.
std::string layout_tag() {
  return std::string("aief ") + kVersionString + " " + std::to_string(sizeof(ExtractorOptions)) +
         "." + std::to_string(sizeof(Keypoint)) + "." + std::to_string(sizeof(ExtractionInfo)) +
         "." + std::to_string(sizeof(SweepPoint)) + "." + std::to_string(sizeof(Match)) + "." +
         std::to_string(sizeof(Homography));
}

// The engine's Features in a state (AdaptResult's two): one list for writing and reading.
template <class State, class FeaturesRef>
void features_fields(State& state, FeaturesRef& f) {
  state.fields(f.image_width, f.image_height, f.keypoints, f.descriptors, f.info, f.descriptor);
}

class StateWriter {
 public:
  StateWriter() { put_string(layout_tag()); }
  template <typename T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  template <typename T>
  void put_vector(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(static_cast<std::uint64_t>(values.size()));
    bytes_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }
  void put_string(const std::string& text) {
    put(static_cast<std::uint64_t>(text.size()));
    bytes_ += text;
  }
  // Each value in order, as its type is written (StateReader::fields reads them back).
  template <typename... T>
  void fields(const T&... values) {
    (field(values), ...);
  }
  py::bytes bytes() const { return py::bytes(bytes_); }

 private:
  template <typename T>
  void field(const T& value) {
    put(value);
  }
  template <typename T>
  void field(const std::vector<T>& values) {
    put_vector(values);
  }
  void field(const std::string& text) { put_string(text); }
  void field(const Features& features) { features_fields(*this, features); }

  std::string bytes_;
};

class StateReader {
 public:
  StateReader(const py::bytes& state, const char* what) : bytes_(state), what_(what) {
    const std::string tag = get_string();
    if (tag != layout_tag())
      throw Error(std::string("cannot unpickle aief.") + what_ + ": it was pickled by '" + tag +
                  "', this is '" + layout_tag() +
                  "' (pickles go between processes of one aief build)");
  }
  template <typename T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    std::memcpy(&value, take(sizeof(T)), sizeof(T));
    return value;
  }
  template <typename T>
  std::vector<T> get_vector() {
    const auto count = get<std::uint64_t>();
    if (count > (bytes_.size() - at_) / sizeof(T)) cut_short();
    std::vector<T> values(count);
    std::memcpy(values.data(), take(count * sizeof(T)), count * sizeof(T));
    return values;
  }
  std::string get_string() {
    const auto size = get<std::uint64_t>();
    if (size > bytes_.size() - at_) cut_short();
    return std::string(take(size), size);
  }
  // Each value in order, read as StateWriter::fields wrote it.
  template <typename... T>
  void fields(T&... values) {
    (field(values), ...);
  }
  void expect_end() const {
    if (at_ != bytes_.size())
      throw Error(std::string("cannot unpickle aief.") + what_ + ": trailing bytes");
  }

 private:
  const char* take(std::size_t size) {
    if (size > bytes_.size() - at_) cut_short();
    const char* data = bytes_.data() + at_;
    at_ += size;
    return data;
  }
  [[noreturn]] void cut_short() const {
    throw Error(std::string("cannot unpickle aief.") + what_ + ": the state is cut short");
  }
  template <typename T>
  void field(T& value) {
    value = get<T>();
  }
  template <typename T>
  void field(std::vector<T>& values) {
    values = get_vector<T>();
  }
  void field(std::string& text) { text = get_string(); }
  void field(Features& features) {
    features_fields(*this, features);
    if (features.descriptors.size() != features.keypoints.size())
      throw Error(std::string("cannot unpickle aief.") + what_ +
                  ": keypoints and descriptors differ in number");
  }

  std::string bytes_;
  const char* what_;
  std::size_t at_ = 0;
};

// AdaptResult's state: one list for writing and reading.
template <class State, class Result>
void adapt_result_fields(State& state, Result& r) {
  state.fields(r.found, r.threshold, r.chosen_index, r.image_entropy_bits, r.curve, r.features_a,
               r.features_b, r.matches, r.homography.found, r.homography.H,
               r.homography.inlier_mask, r.homography.inliers, r.homography.failure);
}

py::bytes adapt_result_state(const AdaptResult& r) {
  StateWriter out;
  adapt_result_fields(out, r);
  return out.bytes();
}

AdaptResult adapt_result_from(const py::bytes& state) {
  StateReader in(state, "AdaptResult");
  AdaptResult r;
  adapt_result_fields(in, r);
  in.expect_end();
  return r;
}

// Pickle protocols 0 and 1 do not go through __getstate__ alone: Python's default reduction for
// them (copyreg._reduce_ex, also what a direct obj.__reduce__() runs) builds the object by
// calling its base's constructor, which a pybind11 class cannot do (it aborted the interpreter:
// "instance allocation failed"). Every protocol, and __reduce__, gets the reduction protocol 2
// makes: copyreg.__newobj__(type) (an instance not yet constructed), then __setstate__(state).
py::tuple reduction(const py::object& self) {
  return py::make_tuple(py::module_::import("copyreg").attr("__newobj__"),
                        py::make_tuple(py::type::of(self)), self.attr("__getstate__")());
}

template <class Class>
void reduce_for_every_protocol(Class& cls) {
  cls.def(
      "__reduce_ex__", [](const py::object& self, int /*protocol*/) { return reduction(self); },
      py::arg("protocol"));
  cls.def("__reduce__", &reduction);
}

}  // namespace

void bind_pickling(py::module_& m) {
  auto extractor = py::reinterpret_borrow<py::class_<PyExtractor>>(m.attr("Extractor"));
  extractor.def(py::pickle(
      [](const PyExtractor& e) {
        // A carried F and its sweep in progress are no options: a copy would start the video
        // again (before, it silently did).
        if (e.options().carried_threshold && e.frames() > 0)
          throw Error(
              "cannot pickle or copy an aief.Extractor(threshold='carried') "
              "after its first frame: "
              "the F it carries and its sweep in progress depend on the frames it has seen, "
              "which a copy would not have; "
              "copy it before its first frame, or extract the whole video with one extractor");
        StateWriter out;
        out.put(e.options());
        // The keywords it was made from, as given: aief.adapt resolves them again for the sweep.
        out.put(static_cast<std::uint64_t>(e.given().size()));
        for (const option_table::GivenOption& g : e.given())
          out.fields(std::string(g.row->key), g.text, g.named);
        return out.bytes();
      },
      [](const py::bytes& state) {
        StateReader in(state, "Extractor");
        const auto options = in.get<ExtractorOptions>();
        std::vector<option_table::GivenOption> given;
        for (auto count = in.get<std::uint64_t>(); count > 0; --count) {
          std::string key, text, named;
          in.fields(key, text, named);
          given.push_back({&option_table::row(key), text, named});
        }
        in.expect_end();
        return std::make_unique<PyExtractor>(options, std::move(given));  // validates the options
      }));
  reduce_for_every_protocol(extractor);

  auto features = py::reinterpret_borrow<py::class_<PyFeatures>>(m.attr("Features"));
  features.def(py::pickle(
      [](const py::object& self) {
        const PyFeatures& f = features_of(self);
        return py::make_tuple(f.keypoints, f.size, f.angle, f.response, f.octave, f.descriptors,
                              f.info, f.image_width, f.image_height,
                              std::string(to_string(f.descriptor)));
      },
      [](const py::tuple& t) {
        // 9 fields: pickled before the box descriptor, so rBRIEF.
        if (t.size() != 9 && t.size() != 10)
          throw Error("cannot unpickle aief.Features: expected 10 fields, got " +
                      std::to_string(t.size()));
        PyFeatures f;
        f.keypoints = t[0].cast<py::array_t<float>>();
        f.size = t[1].cast<py::array_t<float>>();
        f.angle = t[2].cast<py::array_t<float>>();
        f.response = t[3].cast<py::array_t<float>>();
        f.octave = t[4].cast<py::array_t<std::int32_t>>();
        f.descriptors = t[5].cast<py::array_t<std::uint8_t>>();
        f.info = t[6].cast<py::dict>();
        f.image_width = t[7].cast<int>();
        f.image_height = t[8].cast<int>();
        if (t.size() == 10) f.descriptor = parse_descriptor_kind(t[9].cast<std::string>());
        return f;
      }));
  reduce_for_every_protocol(features);

  auto adapt_result = py::reinterpret_borrow<py::class_<AdaptResult>>(m.attr("AdaptResult"));
  adapt_result.def(py::pickle(&adapt_result_state, &adapt_result_from));
  reduce_for_every_protocol(adapt_result);
}

}  // namespace aief::python
