# cmake --install: headers, libraries, the aief tool, a CMake package (find_package(aief) ->
# aief::aief, aief::io) and a pkg-config file.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS aief aief_io EXPORT aiefTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(TARGET aief_opencv)
  install(TARGETS aief_opencv EXPORT aiefTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
endif()
if(TARGET aief_cli)
  install(TARGETS aief_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/aief DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES ${PROJECT_BINARY_DIR}/generated/aief/version.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/aief)
# io headers say #include "io/...": they live under include/aief/io, with include/aief on the path.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/io/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/aief/io FILES_MATCHING PATTERN "*.hpp")

install(EXPORT aiefTargets NAMESPACE aief:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/aief)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/aiefConfig.cmake.in ${PROJECT_BINARY_DIR}/aiefConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/aief)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/aiefConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/aiefConfig.cmake ${PROJECT_BINARY_DIR}/aiefConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/aief)

file(RELATIVE_PATH AIEF_PC_UP /root/${CMAKE_INSTALL_LIBDIR}/pkgconfig /root)  # e.g. ../.. from lib/pkgconfig
configure_file(${PROJECT_SOURCE_DIR}/cmake/aief.pc.in ${PROJECT_BINARY_DIR}/aief.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/aief.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
