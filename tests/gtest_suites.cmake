# Writes CTEST_FILE: one CTest test per GoogleTest suite of TEST_EXECUTABLE, run as
# `TEST_EXECUTABLE --gtest_filter=Suite.*`. Run after each build of the executable
# (tests/CMakeLists.txt, wavetrace_add_gtest_suites).
#
# One process per suite, not per test: every process of a program that links OpenImageIO
# spends about half a second in the dynamic loader (Debian's OpenImageIO pulls in some 250
# shared libraries), which for ~380 one-test processes was a fifth of the suite's CPU time.
#
# Inputs: TEST_EXECUTABLE, CTEST_FILE, WORKING_DIRECTORY, LABELS (a ,-list, may be empty),
# COSTS (a ,-list of Suite=cost: CTest starts the costliest tests first when it has not yet
# timed them, so that a long suite does not start last in a fresh build tree).
string(REPLACE "," ";" LABELS "${LABELS}")
string(REPLACE "," ";" COSTS "${COSTS}")
execute_process(COMMAND "${TEST_EXECUTABLE}" --gtest_list_tests
  WORKING_DIRECTORY "${WORKING_DIRECTORY}"
  OUTPUT_VARIABLE listing ERROR_VARIABLE errors RESULT_VARIABLE status TIMEOUT 60)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${TEST_EXECUTABLE} --gtest_list_tests failed (${status}): ${errors}")
endif()

set(script "")
string(REPLACE "\n" ";" lines "${listing}")
foreach(line IN LISTS lines)
  # A suite's line starts in column 0 and ends its name with a dot ("Suite." or, for value-
  # and type-parameterized suites, "Prefix/Suite."); its tests follow, indented.
  if(NOT line MATCHES "^([A-Za-z0-9_/]+)\\.")
    continue()
  endif()
  set(suite "${CMAKE_MATCH_1}")
  set(cost 1)
  foreach(entry IN LISTS COSTS)
    if(entry MATCHES "^${suite}=([0-9]+)$")
      set(cost "${CMAKE_MATCH_1}")
    endif()
  endforeach()
  string(APPEND script
    "add_test([==[${suite}]==] [==[${TEST_EXECUTABLE}]==] [==[--gtest_filter=${suite}.*]==])\n"
    "set_tests_properties([==[${suite}]==] PROPERTIES WORKING_DIRECTORY [==[${WORKING_DIRECTORY}]==]"
    " COST ${cost}")
  if(LABELS)
    string(APPEND script " LABELS [==[${LABELS}]==]")
  endif()
  string(APPEND script ")\n")
endforeach()
file(WRITE "${CTEST_FILE}" "${script}")
