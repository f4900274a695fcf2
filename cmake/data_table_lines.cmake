# The lines of a table kept as data (data/orb_pattern_31.txt, data/box_descriptor/<name>.txt), for
# the generators that turn one into C++ (cmake/generate_orb_pattern.cmake,
# cmake/generate_box_table.cmake): each line stripped, blank and '#' comment lines left out.
function(aief_data_table_lines input out_var)
  file(STRINGS "${input}" lines)
  set(kept "")
  foreach(line IN LISTS lines)
    string(STRIP "${line}" line)
    if(NOT line STREQUAL "" AND NOT line MATCHES "^#")
      list(APPEND kept "${line}")
    endif()
  endforeach()
  set(${out_var} "${kept}" PARENT_SCOPE)
endfunction()
