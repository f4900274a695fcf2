# cmake --install: headers, libraries, the aief tool, a CMake package (find_package(aief) ->
# aief::aief, and aief::io, aief::opencv when built) and a pkg-config file for the engine. The
# same CMake package in the build folder, for use without installing.
# Each component has its own export file, so the package config loads OpenCV only for the
# components that link it (cmake/aiefConfig.cmake.in). Every file belongs to one install component
# (runtime: shared libraries; dev: headers, archives, .so links, CMake and pkg-config files; tool;
# python), which cmake/packaging.cmake turns into one Debian package each.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS aief EXPORT aiefTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime NAMELINK_COMPONENT dev
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
set(AIEF_INSTALLED_COMPONENTS "")
foreach(component IN ITEMS io opencv)
  if(TARGET aief_${component})
    install(TARGETS aief_${component} EXPORT aief_${component}Targets
            ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev
            LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime NAMELINK_COMPONENT dev)
    install(EXPORT aief_${component}Targets NAMESPACE aief:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/aief COMPONENT dev)
    export(EXPORT aief_${component}Targets NAMESPACE aief:: FILE ${PROJECT_BINARY_DIR}/aief_${component}Targets.cmake)
    list(APPEND AIEF_INSTALLED_COMPONENTS ${component})
  endif()
endforeach()
if(TARGET aief_cli)
  install(TARGETS aief_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT tool)
  get_target_property(aief_library_type aief TYPE)
  if(aief_library_type STREQUAL "SHARED_LIBRARY")  # the installed tool finds libaief.so wherever the prefix is moved
    set_target_properties(aief_cli PROPERTIES INSTALL_RPATH "$ORIGIN/../${CMAKE_INSTALL_LIBDIR}")
  endif()
endif()
# Every public header, present and future; the adapter's only when the adapter is built.
if(TARGET aief_opencv)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/aief DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT dev)
else()
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/aief DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT dev
          PATTERN opencv.hpp EXCLUDE PATTERN feature2d.hpp EXCLUDE PATTERN cv_image_view.hpp EXCLUDE
          PATTERN orbslam*_extractor*.hpp EXCLUDE)
endif()
install(FILES ${PROJECT_BINARY_DIR}/generated/aief/version.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/aief COMPONENT dev)
# io headers say #include "io/...": they live under include/aief/io, with include/aief on the path.
if(TARGET aief_io)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/io/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/aief/io COMPONENT dev FILES_MATCHING PATTERN "*.hpp")
endif()

install(EXPORT aiefTargets NAMESPACE aief:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/aief COMPONENT dev)
# The build tree is a package too: aiefConfig.cmake and the targets files beside it in the build
# folder, so find_package(aief) with aief_DIR=<build folder> uses the built libraries in place
# (tests/consumer/run.sh --build-tree).
export(EXPORT aiefTargets NAMESPACE aief:: FILE ${PROJECT_BINARY_DIR}/aiefTargets.cmake)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/aiefConfig.cmake.in ${PROJECT_BINARY_DIR}/aiefConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/aief)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/aiefConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/aiefConfig.cmake ${PROJECT_BINARY_DIR}/aiefConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/aief COMPONENT dev)

# pkg-config. A static libaief needs TBB and pthreads on the consumer's link line; putting them in
# Libs (not Libs.private behind tbb.pc) makes plain `pkg-config --libs aief` link, and does not
# depend on the distribution shipping tbb.pc.
file(RELATIVE_PATH AIEF_PC_UP /${CMAKE_INSTALL_LIBDIR}/pkgconfig /)  # "../.." from lib/pkgconfig
string(REGEX REPLACE "/$" "" AIEF_PC_UP "${AIEF_PC_UP}")
get_target_property(aief_library_type aief TYPE)
if(aief_library_type STREQUAL "STATIC_LIBRARY")
  set(AIEF_PC_LIBS "-laief -ltbb -lpthread")
  set(AIEF_PC_LIBS_PRIVATE "")
else()
  set(AIEF_PC_LIBS "-laief")
  set(AIEF_PC_LIBS_PRIVATE "-ltbb -lpthread")
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/aief.pc.in ${PROJECT_BINARY_DIR}/aief.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/aief.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig COMPONENT dev)
# aief-io.pc and aief-opencv.pc, one per component built: `pkg-config --cflags --libs aief-opencv`
# links the cv::Feature2D adapter and the ORB-SLAM drop-ins (their headers include OpenCV's, so
# opencv4 is required publicly); `aief-io` the image and result files. A static libaief_io also
# needs, on the consumer's link line, what it links privately: OpenCV, and HDF5 and SQLite when
# it was built with them (the AIEF_HAVE_* definitions say so, in Cflags as in aief::io).
if(TARGET aief_io)
  get_target_property(aief_io_type aief_io TYPE)
  get_target_property(aief_io_definitions aief_io INTERFACE_COMPILE_DEFINITIONS)
  set(AIEF_PC_COMPONENT io)
  set(AIEF_PC_DESCRIPTION "aief's image and result files: images through OpenCV, JSON, YAML, hloc's HDF5, COLMAP's database")
  set(AIEF_PC_REQUIRES aief)
  set(AIEF_PC_CFLAGS "-I\${includedir}/aief")
  if(aief_io_type STREQUAL "STATIC_LIBRARY")
    string(APPEND AIEF_PC_REQUIRES " opencv4")
  endif()
  # Each optional part: its definition, then the pkg-config package a static build links it by.
  set(aief_io_optional_definitions AIEF_HAVE_HDF5 AIEF_HAVE_COLMAP_EXPORT)
  set(aief_io_optional_packages hdf5 sqlite3)
  foreach(definition package IN ZIP_LISTS aief_io_optional_definitions aief_io_optional_packages)
    if(definition IN_LIST aief_io_definitions)
      string(APPEND AIEF_PC_CFLAGS " -D${definition}")
      if(aief_io_type STREQUAL "STATIC_LIBRARY")
        string(APPEND AIEF_PC_REQUIRES " ${package}")
      endif()
    endif()
  endforeach()
  configure_file(${PROJECT_SOURCE_DIR}/cmake/aief-component.pc.in ${PROJECT_BINARY_DIR}/aief-io.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/aief-io.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig COMPONENT dev)
endif()
if(TARGET aief_opencv)
  set(AIEF_PC_COMPONENT opencv)
  set(AIEF_PC_DESCRIPTION "aief's OpenCV adapter: cv::Feature2D, cv::Mat views, the ORB-SLAM2 and ORB-SLAM3 drop-ins")
  set(AIEF_PC_REQUIRES "aief opencv4")
  set(AIEF_PC_CFLAGS "")
  configure_file(${PROJECT_SOURCE_DIR}/cmake/aief-component.pc.in ${PROJECT_BINARY_DIR}/aief-opencv.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/aief-opencv.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig COMPONENT dev)
endif()

# tests/ builds every tests/test_*.cpp; without the adapter its tests have nothing to link.
# (CTest then lists them as *_NOT_BUILT; skipping them belongs in tests/CMakeLists.txt.)
if(NOT TARGET aief_opencv)
  foreach(adapter_test IN ITEMS test_opencv_adapter test_orbslam2_dropin test_orbslam3_dropin)
    if(TARGET ${adapter_test})
      set_target_properties(${adapter_test} PROPERTIES EXCLUDE_FROM_ALL ON)
    endif()
  endforeach()
endif()
