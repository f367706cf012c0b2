# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
# Every CMakeLists.txt lists its sources by name (no globs: a target's sources
# are read off its list, and a stray file is not picked up). The opposite
# mistake, a .cpp file that no list names, would never be compiled (a test
# file whose tests never run); this check makes it a configure error.
# A subfolder with its own CMakeLists.txt checks its own sources.
#   dda_check_sources_listed(<folder> <source>...)  # sources relative to <folder>
function(dda_check_sources_listed folder)
  file(GLOB_RECURSE unlisted RELATIVE ${folder} ${folder}/*.cpp)
  file(GLOB_RECURSE own_lists RELATIVE ${folder} ${folder}/*/CMakeLists.txt)
  foreach(list_file ${own_lists})
    get_filename_component(sub ${list_file} DIRECTORY)
    list(FILTER unlisted EXCLUDE REGEX "^${sub}/")
  endforeach()
  if(ARGN)
    list(REMOVE_ITEM unlisted ${ARGN})
  endif()
  if(unlisted)
    list(JOIN unlisted ", " names)
    message(FATAL_ERROR "${folder}: ${names} in no source list; add to ${folder}/CMakeLists.txt (or remove)")
  endif()
endfunction()
