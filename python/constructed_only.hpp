#pragma once
// An object made by `Cls.__new__(Cls)` alone holds no C++ object (unpickling makes one that way,
// then __setstate__ builds it). pybind11 hands such an object's methods memory it allocates raw
// on the spot (type_caster_generic::load_value), so `aief.Extractor.__new__(aief.Extractor)
// .options` crashed. A bound class whose caster is this one refuses it with aief::Error ("this
// aief.Extractor holds nothing ...") in every method, property and argument at once:
//   namespace pybind11::detail {
//   template <> class type_caster<C> : public aief::python::ConstructedOnlyCaster<C> {};
//   }
#include <string>
#include <typeinfo>

#include <pybind11/pybind11.h>

#include "aief/error.hpp"

namespace aief::python {

template <class T>
class ConstructedOnlyCaster : public pybind11::detail::type_caster_base<T> {
 public:
  bool load(pybind11::handle source, bool convert) {
    namespace py = pybind11;
    if (source && py::isinstance<T>(source)) {
      auto* instance = reinterpret_cast<py::detail::instance*>(source.ptr());
      const auto* type = py::detail::get_type_info(typeid(T));
      if (!instance->get_value_and_holder(type).holder_constructed()) {
        const std::string name = py::str(py::type::of(source).attr("__name__"));
        throw Error("this aief." + name + " holds nothing: it was made by " + name +
                    ".__new__ alone, not by its constructor or unpickling");
      }
    }
    return py::detail::type_caster_base<T>::load(source, convert);
  }
};

}  // namespace aief::python
