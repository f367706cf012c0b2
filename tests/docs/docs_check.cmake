# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
# The docs stay short and their links resolve (cmake -P, a second or less):
#  - every docs/*.md and README.md is at most 400 lines, except the reports
#    the paper scripts generate from their runs (docs/validation.md: its
#    length is set by the data it tabulates);
#  - every relative link `](path)` in README.md and docs/*.md names a file that
#    exists (the part after `#` is not checked);
#  - every `docs/<name>.md` named in the README, the docs, the sources, the
#    scripts, the tests and the CMake files exists.
# Run: cmake -DSOURCE=<repository root> -P tests/docs/docs_check.cmake
cmake_minimum_required(VERSION 3.20)
if(NOT SOURCE)
  message(FATAL_ERROR "docs_check: pass -DSOURCE=<repository root>")
endif()
set(max_lines 400)
set(generated docs/validation.md)
set(failures "")

file(GLOB docs RELATIVE ${SOURCE} ${SOURCE}/docs/*.md)
list(APPEND docs README.md)
foreach(doc IN LISTS docs)
  file(READ ${SOURCE}/${doc} text)
  # `;` separates CMake list items and `[` `]` group them: neither may stay.
  string(REPLACE ";" " " text "${text}")
  string(REPLACE "[" "<" text "${text}")
  string(REPLACE "]" ">" text "${text}")
  string(REGEX MATCHALL "\n" newlines "${text}")
  list(LENGTH newlines n)
  if(n GREATER max_lines AND NOT doc IN_LIST generated)
    string(APPEND failures "${doc} has ${n} lines (at most ${max_lines}: split it by topic or cut repetition)\n")
  endif()
  get_filename_component(dir ${SOURCE}/${doc} DIRECTORY)
  string(REGEX MATCHALL ">\\([^)# ]+" links "${text}")
  foreach(link IN LISTS links)
    string(SUBSTRING "${link}" 2 -1 target)
    if(target MATCHES "^[a-z]+:" OR target MATCHES "^\\.\\./shared/")  # a URL; the paper's folder
      continue()
    endif()
    if(NOT EXISTS "${dir}/${target}")
      string(APPEND failures "${doc} links to ${target}, which does not exist\n")
    endif()
  endforeach()
endforeach()

file(GLOB_RECURSE sources RELATIVE ${SOURCE}
     ${SOURCE}/engine/* ${SOURCE}/scripting/* ${SOURCE}/render/* ${SOURCE}/tests/* ${SOURCE}/bench/*
     ${SOURCE}/scripts/* ${SOURCE}/cmake/* ${SOURCE}/fuzz/* ${SOURCE}/.ci/* ${SOURCE}/docs/*.md)
list(APPEND sources README.md CMakeLists.txt)
list(FILTER sources INCLUDE REGEX "(\\.(cpp|hpp|h|lua|cmake|py|sh|md|txt)|/run)$")
foreach(f IN LISTS sources)
  file(READ ${SOURCE}/${f} text)
  string(REPLACE ";" " " text "${text}")
  string(REPLACE "[" "<" text "${text}")
  string(REGEX MATCHALL "docs/[A-Za-z0-9_]+\\.md" named "${text}")
  list(REMOVE_DUPLICATES named)
  foreach(d IN LISTS named)
    if(NOT EXISTS ${SOURCE}/${d})
      string(APPEND failures "${f} names ${d}, which does not exist\n")
    endif()
  endforeach()
endforeach()

if(failures)
  message(FATAL_ERROR "docs_check:\n${failures}")
endif()
list(LENGTH docs ndocs)
message(STATUS "docs_check: ${ndocs} docs within ${max_lines} lines, their links resolve")
