# Turns data/orb_pattern_31.txt (the learned ORB pattern, kept as data) into a C++ initializer
# list, so the engine needs no file at run time. Called at configure time by core/CMakeLists.txt.
include(${CMAKE_CURRENT_LIST_DIR}/data_table_lines.cmake)

function(aief_generate_orb_pattern input output)
  aief_data_table_lines("${input}" lines)
  set(body "")
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "[ \t]+" ", " values "${line}")
    string(APPEND body "    {${values}},\n")
  endforeach()
  list(LENGTH lines count)
  if(NOT count EQUAL 256)
    message(FATAL_ERROR "${input}: expected 256 pattern lines, found ${count}")
  endif()
  file(CONFIGURE OUTPUT "${output}" CONTENT "// Generated from data/orb_pattern_31.txt; do not edit.\n${body}")
endfunction()
