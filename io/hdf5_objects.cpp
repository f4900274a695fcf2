#include "io/hdf5_objects.hpp"

#include <string>

namespace aief::io::hdf5 {

void silence_hdf5() {
  thread_local const bool silenced = H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) >= 0;
  (void)silenced;
}

std::string hdf5_reason() {
  std::string innermost;
  const auto visit = [](unsigned, const H5E_error2_t* error, void* data) -> herr_t {
    if (error->desc) *static_cast<std::string*>(data) = error->desc;
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, visit, &innermost);
  H5Eclear2(H5E_DEFAULT);
  const std::string marker = "error message = '";
  const std::size_t at = innermost.find(marker);
  if (at != std::string::npos) {
    const std::size_t begin = at + marker.size();
    return innermost.substr(begin, innermost.find('\'', begin) - begin);
  }
  return innermost;
}

bool exists(hid_t file, const std::string& path) {
  silence_hdf5();
  std::size_t at = 0;
  while (true) {
    at = path.find('/', at + 1);
    const std::string prefix = path.substr(0, at);
    if (H5Lexists(file, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (at == std::string::npos) return true;
  }
}

hid_t with_parents() {
  static const hid_t list = [] {
    const hid_t made = H5Pcreate(H5P_LINK_CREATE);
    H5Pset_create_intermediate_group(made, 1);
    return made;
  }();
  return list;
}

Handle create_group(hid_t file, const std::string& name, const std::string& path) {
  Handle group(H5Gcreate2(file, name.c_str(), with_parents(), H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!group.ok())
    throw Error(hdf5_reason() + " (creating group '" + name + "' in '" + path + "')");
  return group;
}

void remove_group(hid_t file, const std::string& name) {
  if (exists(file, name)) H5Ldelete(file, name.c_str(), H5P_DEFAULT);
}

Handle open_group_if_any(hid_t file, const std::string& name) {
  silence_hdf5();
  return Handle(H5Gopen2(file, name.c_str(), H5P_DEFAULT), H5Gclose);
}

std::string string_attribute(hid_t object, const char* name) {
  if (H5Aexists(object, name) <= 0) return "";
  const Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
  const Handle stored(H5Aget_type(attribute.get()), H5Tclose);
  if (H5Tget_class(stored.get()) != H5T_STRING) return "";
  if (H5Tis_variable_str(stored.get()) <= 0) {  // fixed length
    std::string value(H5Tget_size(stored.get()), '\0');
    if (H5Aread(attribute.get(), stored.get(), value.data()) < 0) return "";
    return value.substr(0, value.find('\0'));
  }
  const Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), H5T_VARIABLE);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  char* text = nullptr;
  if (H5Aread(attribute.get(), type.get(), &text) < 0 || !text) return "";
  std::string value(text);
  H5free_memory(text);
  return value;
}

void write_string_attribute(hid_t object, const char* name, const std::string& value,
                            StringLength length) {
  const Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  const bool fixed = length == StringLength::fixed;
  H5Tset_size(type.get(), fixed ? std::max<std::size_t>(value.size(), 1) : H5T_VARIABLE);
  if (fixed) H5Tset_strpad(type.get(), H5T_STR_NULLPAD);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  const Handle attribute(
      H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  const char* text = value.c_str();
  const void* buffer = fixed ? static_cast<const void*>(text) : static_cast<const void*>(&text);
  if (!attribute.ok() || H5Awrite(attribute.get(), type.get(), buffer) < 0)
    throw Error(hdf5_reason() + " (attribute '" + name + "')");
}

std::string damaged_file(const std::string& path, const std::string& hdf5_said) {
  return "cannot open '" + path + "' as an HDF5 file: it is damaged or cut short" +
         (hdf5_said.empty() ? std::string() : " (libhdf5: " + hdf5_said + ")") +
         "; if it is the output of a run that was killed or stopped, move it away and run that "
         "command again, which writes it anew";
}

}  // namespace aief::io::hdf5
