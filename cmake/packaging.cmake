# `cpack -G DEB`: one Debian package per install component (cmake/install.cmake), from a shared
# build installed under /usr (docs/install.md; scripts/ci_packages builds, installs and removes them):
#   libaief<major>.<minor>  the shared libraries libaief, libaief_io, libaief_opencv (SONAME .so.<major>.<minor>:
#                           the ABI may change with every 0.x release)
#   libaief-dev             headers, the .so links, the same libraries as static archives, the CMake
#                           package (find_package(aief)) and pkg-config's aief.pc
#   aief                    the command-line tool
#   python3-aief            the Python module, for the Debian python3 it was built with
# Depends: dpkg-shlibdeps for the system libraries, the runtime package at this exact version
# for the others, and libaief-dev needs what aiefConfig.cmake looks for (TBB, OpenCV).
get_target_property(aief_library_type aief TYPE)
set(aief_packaged_libraries aief aief_io aief_opencv)
set(aief_soversion ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR})

if(aief_library_type STREQUAL "SHARED_LIBRARY")
  # The static archives beside the shared libraries, from the same (position-independent) objects:
  # no second compilation. Each archive also takes the objects the library pulls in from object
  # libraries (the per-ISA kernels).
  foreach(library IN LISTS aief_packaged_libraries)
    if(NOT TARGET ${library})
      continue()
    endif()
    set_target_properties(${library} PROPERTIES VERSION ${PROJECT_VERSION} SOVERSION ${aief_soversion})
    get_target_property(sources ${library} SOURCES)
    list(FILTER sources INCLUDE REGEX "^\\$<TARGET_OBJECTS:")
    add_library(${library}_archive STATIC $<TARGET_OBJECTS:${library}> ${sources})
    set_target_properties(${library}_archive PROPERTIES OUTPUT_NAME ${library})
    install(TARGETS ${library}_archive ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev)
  endforeach()
endif()

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME aief)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "ORB features with an adaptive information-entropy block mask (AIEF)")
set(CPACK_PACKAGE_CONTACT "aief maintainers <aief@localhost>")
set(CPACK_PACKAGE_DIRECTORY ${PROJECT_BINARY_DIR}/packages)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL runtime dev)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # name_version_arch.deb
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# dpkg-shlibdeps finds libaief*.so.* of this build here (their package comes from the component
# dependencies below, not from dpkg's database).
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS ${PROJECT_BINARY_DIR}/core ${PROJECT_BINARY_DIR}/io ${PROJECT_BINARY_DIR}/opencv)
set(CPACK_DEBIAN_ENABLE_COMPONENT_DEPENDS ON)

set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME libaief${aief_soversion})
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SECTION libs)
set(CPACK_COMPONENT_RUNTIME_DESCRIPTION "AIEF ORB feature extraction: shared libraries
 The engine (libaief), its image and result files (libaief_io) and its OpenCV adapter with the
 ORB-SLAM2/3 drop-ins (libaief_opencv).")

set(CPACK_DEBIAN_DEV_PACKAGE_NAME libaief-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_COMPONENT_DEV_DEPENDS runtime)
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS "libtbb-dev, libopencv-dev")
set(CPACK_COMPONENT_DEV_DESCRIPTION "AIEF ORB feature extraction: development files
 Headers, shared and static libraries, the CMake package (find_package(aief) -> aief::aief,
 aief::io, aief::opencv) and pkg-config's aief.pc.")

if(TARGET aief_cli)
  list(APPEND CPACK_COMPONENTS_ALL tool)
  set(CPACK_DEBIAN_TOOL_PACKAGE_NAME aief)
  set(CPACK_DEBIAN_TOOL_PACKAGE_SECTION science)
  set(CPACK_COMPONENT_TOOL_DEPENDS runtime)
  set(CPACK_COMPONENT_TOOL_DESCRIPTION "AIEF ORB feature extraction: the aief command line
 extract, match, adapt, eval, bench and the batch, HDF5 and COLMAP outputs.")
endif()

if(TARGET aief_python)
  list(APPEND CPACK_COMPONENTS_ALL python)
  set(CPACK_DEBIAN_PYTHON_PACKAGE_NAME python3-aief)
  set(CPACK_DEBIAN_PYTHON_PACKAGE_SECTION python)
  set(CPACK_COMPONENT_PYTHON_DEPENDS runtime)
  math(EXPR aief_next_python_minor "${Python_VERSION_MINOR} + 1")
  # The extension is built for this CPython (its file name says cpython-3XY).
  set(CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS
      "python3 (>= ${Python_VERSION_MAJOR}.${Python_VERSION_MINOR}), python3 (<< ${Python_VERSION_MAJOR}.${aief_next_python_minor}), python3-numpy")
  set(CPACK_COMPONENT_PYTHON_DESCRIPTION "AIEF ORB feature extraction: the Python module aief
 Extraction, Hamming matching, RANSAC and the adaptive threshold sweep on numpy arrays.")
endif()

# The licence in every package (LICENSE, NOTICE): Debian's machine-readable copyright file, naming
# the third-party data NOTICE names, at share/doc/<package>/copyright, with LICENSE and NOTICE
# beside it (the Apache License asks that NOTICE travel with every copy).
foreach(component IN LISTS CPACK_COMPONENTS_ALL)
  string(TOUPPER ${component} component_upper)
  set(package_doc ${CMAKE_INSTALL_DATAROOTDIR}/doc/${CPACK_DEBIAN_${component_upper}_PACKAGE_NAME})
  install(FILES ${PROJECT_SOURCE_DIR}/cmake/debian_copyright DESTINATION ${package_doc}
          RENAME copyright COMPONENT ${component})
  install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/NOTICE DESTINATION ${package_doc}
          COMPONENT ${component})
endforeach()

include(CPack)
