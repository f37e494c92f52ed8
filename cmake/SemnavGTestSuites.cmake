# cmake -P script, run after a GoogleTest executable is linked: writes CTEST_FILE
# with one ctest per test suite of TEST_EXECUTABLE (--gtest_filter=Suite.*),
# run in WORKING_DIRECTORY, its COST the number of its tests (ctest starts
# costly ones first when it has no timings yet). Suites whose tests are all
# DISABLED_ are left out.
foreach(var TEST_EXECUTABLE CTEST_FILE WORKING_DIRECTORY)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "SemnavGTestSuites.cmake: ${var} is not set")
  endif()
endforeach()
execute_process(COMMAND "${TEST_EXECUTABLE}" --gtest_list_tests
  WORKING_DIRECTORY "${WORKING_DIRECTORY}" TIMEOUT 60
  OUTPUT_VARIABLE listing ERROR_VARIABLE errors RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${TEST_EXECUTABLE} --gtest_list_tests failed (${rc}): ${errors}")
endif()
string(REPLACE ";" "\\;" listing "${listing}")
string(REPLACE "\n" ";" lines "${listing}")
set(suite "")
set(enabled "")
foreach(line IN LISTS lines)
  if(line MATCHES "^([^ #][^ ]*)\\.")
    set(suite "${CMAKE_MATCH_1}")
  elseif(line MATCHES "^  ([^ ]+)" AND suite AND NOT suite MATCHES "^DISABLED_|/DISABLED_"
         AND NOT CMAKE_MATCH_1 MATCHES "^DISABLED_")
    list(APPEND enabled "${suite}")
  endif()
endforeach()
set(suites ${enabled})
list(REMOVE_DUPLICATES suites)
set(out "")
foreach(s IN LISTS suites)
  set(cases ${enabled})
  list(FILTER cases INCLUDE REGEX "^${s}$")
  list(LENGTH cases cost)
  string(APPEND out
    "add_test([==[${s}]==] [==[${TEST_EXECUTABLE}]==] [==[--gtest_filter=${s}.*]==])\n"
    "set_tests_properties([==[${s}]==] PROPERTIES WORKING_DIRECTORY [==[${WORKING_DIRECTORY}]==] COST ${cost})\n")
endforeach()
file(WRITE "${CTEST_FILE}.tmp" "${out}")
file(RENAME "${CTEST_FILE}.tmp" "${CTEST_FILE}")
