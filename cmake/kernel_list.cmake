# The kernel list, read once: AIEF_FOR_EACH_KERNEL in core/kernels/kernel_table.hpp is the list
# (C++ builds the table from it); this is the one place that reads it for anything else. It sets
# AIEF_KERNELS (the names in table order) for simd/CMakeLists.txt, which finds each kernel's
# vector code by name, and writes ${PROJECT_BINARY_DIR}/kernel_list.txt, one name a line, for
# the scripts (scripts/kernel_files.py, bench/kernel_instructions.py). Configure runs again
# whenever the list changes.
set(aief_kernel_list_source ${PROJECT_SOURCE_DIR}/core/kernels/kernel_table.hpp)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${aief_kernel_list_source})
file(STRINGS ${aief_kernel_list_source} aief_kernel_lines REGEX "^  X\\([a-z0-9_]+\\)")
# Each line ends in the macro's backslash: the names alone.
string(REGEX MATCHALL "X\\([a-z0-9_]+\\)" aief_kernel_lines "${aief_kernel_lines}")
set(AIEF_KERNELS "")
foreach(line IN LISTS aief_kernel_lines)
  string(REGEX REPLACE "^X\\(([a-z0-9_]+)\\)$" "\\1" kernel "${line}")
  list(APPEND AIEF_KERNELS ${kernel})
endforeach()
if(NOT AIEF_KERNELS)
  message(FATAL_ERROR "no X(name) line in AIEF_FOR_EACH_KERNEL (${aief_kernel_list_source})")
endif()
list(JOIN AIEF_KERNELS "\n" aief_kernel_lines)
file(CONFIGURE OUTPUT ${PROJECT_BINARY_DIR}/kernel_list.txt CONTENT "${aief_kernel_lines}\n")
