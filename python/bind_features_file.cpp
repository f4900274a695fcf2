// aief.FeaturesFile: the engine's writer of hloc feature files (io::Hdf5File, the writer of
// `aief extract --batch --format h5`), so that the Dask recipe (aief/dask_batch.py) writes its
// shards with the engine's guarantees: a full disk or a failed write stops with aief.Error and
// keeps every group complete before it readable (io/hdf5_file.hpp), where h5py left a file
// nobody could open.
#include <pybind11/stl.h>

#include <array>
#include <memory>
#include <optional>
#include <string>

#include "aief/error.hpp"
#include "aief/match.hpp"
#include "python/bindings.hpp"
#include "python/py_extractor.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_file.hpp"
#include "io/option_record.hpp"
#endif

namespace aief::python {

namespace {

#ifdef AIEF_HAVE_HDF5

// The source record a group keeps: (size in bytes, modification time in ns), as
// aief.dask_batch.source_of gives it (io/source_record.hpp).
io::SourceRecord source_record(const std::string& name, const std::array<long long, 2>& source) {
  io::SourceRecord record;
  record.name = name;
  record.bytes = static_cast<std::uintmax_t>(source[0]);
  record.mtime_ns = source[1];
  return record;
}

// One open file; calls hold the GIL, so a libhdf5 built without its thread-safe option sees one
// caller at a time.
class FeaturesFile {
 public:
  explicit FeaturesFile(const py::object& path)
      : file_(std::make_unique<io::Hdf5File>(filesystem_path(path),
                                             io::Hdf5File::Mode::read_write)) {}

  // Names as batch_inputs gives them (os.fsdecode): their bytes are the CLI's group names.
  bool is_current(const py::object& name_given, const std::array<long long, 2>& source,
                  const PyExtractor& extractor) const {
    const std::string name = filesystem_path(name_given);
    const io::Hdf5File& file = open();
    return file.features_belong_to(name, source_record(name, source)) &&
           io::option_changes(file.option_record(name), extractor.options()).empty();
  }
  // features: an aief.Features (checked by features_of, which refuses one holding nothing).
  void write(const py::object& name_given, const py::object& features,
             const std::array<long long, 2>& source, const PyExtractor& extractor) {
    const std::string name = filesystem_path(name_given);
    const io::SourceRecord record = source_record(name, source);
    const Features engine = engine_features(features);
    // The group records the extractor's options: they must be the features' own.
    require_same_descriptor(engine.descriptor, "features", extractor.options().descriptor,
                            "the extractor");
    open().write_features(name, engine, &record, &extractor.options());
  }
  void remove(const py::object& name) { open().remove_features(filesystem_path(name)); }
  int writes_on_disk() const { return file_ ? file_->groups_on_disk() : writes_on_disk_; }
  void close() {
    if (!file_) return;
    const std::unique_ptr<io::Hdf5File> file = std::move(file_);
    try {
      file->close();
    } catch (...) {
      writes_on_disk_ = file->groups_on_disk();
      throw;
    }
    writes_on_disk_ = file->groups_on_disk();
  }

 private:
  io::Hdf5File& open() const {
    if (!file_) throw Error("the features file is closed");
    return *file_;
  }
  std::unique_ptr<io::Hdf5File> file_;
  int writes_on_disk_ = 0;  // once closed
};

#else

// A build without libhdf5: the class exists and says why it cannot open a file.
class FeaturesFile {
 public:
  explicit FeaturesFile(const py::object&) {
    throw Error("this aief was built without HDF5 (install libhdf5-dev and rebuild)");
  }
  bool is_current(const py::object&, const std::array<long long, 2>&, const PyExtractor&) const {
    return false;
  }
  void write(const py::object&, const py::object&, const std::array<long long, 2>&,
             const PyExtractor&) {}
  void remove(const py::object&) {}
  int writes_on_disk() const { return 0; }
  void close() {}
};

#endif

}  // namespace
}  // namespace aief::python

// A FeaturesFile made by __new__ alone is refused, not read (python/constructed_only.hpp).
namespace pybind11::detail {
template <>
class type_caster<aief::python::FeaturesFile>
    : public aief::python::ConstructedOnlyCaster<aief::python::FeaturesFile> {};
}  // namespace pybind11::detail

namespace aief::python {

void bind_features_file(py::module_& m) {
  py::class_<FeaturesFile>(
      m, "FeaturesFile",
      "An hloc features file (HDF5) written by the engine's writer, "
      "as aief extract --batch --format h5 writes it: "
      "opened for reading and writing (created when missing). "
      "A failed write (a full disk) raises aief.Error and keeps every group complete before it; "
      "use it as a context manager, or call close() to know that the writes are on disk")
      .def(py::init<const py::object&>(), py::arg("path"))
      .def("is_current", &FeaturesFile::is_current, py::arg("name"), py::arg("source"),
           py::arg("extractor"),
           "Whether `name` is a complete group written from the image file `source` describes "
           "((size in bytes, modification time in ns)) "
           "with options that give what `extractor` would "
           "(the resume rule of aief extract --batch)")
      .def("write", &FeaturesFile::write, py::arg("name"), py::arg("features"), py::arg("source"),
           py::arg("extractor"),
           "Writes the group `name` (replacing one of that name) with the features, "
           "the source record and `extractor`'s option record")
      .def("remove", &FeaturesFile::remove, py::arg("name"),
           "Removes the group `name`, if there is one")
      .def_property_readonly(
          "writes_on_disk", &FeaturesFile::writes_on_disk,
          "How many of this object's writes the file on disk holds: "
          "after a failed write, those before it that reached the disk "
          "(the writes since the last flush are lost when the disk fills at a flush, "
          "as on a file system without fallocate)")
      .def("close", &FeaturesFile::close,
           "Closes the file, raising aief.Error when its last writes could not be stored")
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__",
           [](FeaturesFile& file, const py::object& type, const py::object&, const py::object&) {
             if (type.is_none()) {
               file.close();
               return;
             }
             try {  // already failing: the first error is the one to see
               file.close();
             } catch (const std::exception&) {
             }
           })
      // An open file is no value to send to another process (and Python's default reduction
      // of a pybind11 object aborted the interpreter): refused by name.
      .def("__reduce__",
           [](const py::object&) -> py::object {
             throw Error(
                 "an aief.FeaturesFile (an open file) cannot be pickled or copied: "
                 "send its path and open it where it is needed");
           })
      .def("__reduce_ex__", [](const py::object& self, int) { return self.attr("__reduce__")(); });
}

}  // namespace aief::python
