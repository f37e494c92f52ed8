# semnav_add_library(<module> SOURCES ... DEPENDS ...)
# Creates target semnav_<module> with alias semnav::<module>; public headers in
# libs/<module>/include/semnav/<module>/.
function(semnav_add_library module)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS;PRIVATE_DEPENDS" ${ARGN})
  add_library(semnav_${module} ${ARG_SOURCES})
  add_library(semnav::${module} ALIAS semnav_${module})
  target_include_directories(semnav_${module} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>)
  target_link_libraries(semnav_${module} PUBLIC ${ARG_DEPENDS} PRIVATE ${ARG_PRIVATE_DEPENDS})
  target_compile_options(semnav_${module} PRIVATE -Wall -Wextra)
  set_target_properties(semnav_${module} PROPERTIES POSITION_INDEPENDENT_CODE ON)
endfunction()

# semnav_add_app(<name> SOURCES ... DEPENDS ...)
function(semnav_add_app name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPENDS})
  target_compile_options(${name} PRIVATE -Wall -Wextra)
endfunction()

# semnav_add_test(<name> [SERIAL] [LABELS l] SOURCES ... DEPENDS ...): a GoogleTest executable
# registered with ctest; SERIAL tests run alone (ctest RUN_SERIAL: timing against real-time
# devices) and carry the label `realtime` unless LABELS names another (scripts/sanitize runs
# `realtime|ros1` apart); LABELS for ctest -L.
function(semnav_add_test name)
  cmake_parse_arguments(ARG "SERIAL" "LABELS" "SOURCES;DEPENDS" ${ARGN})
  set(props "")
  # (One label per test: gtest_discover_tests loses a list's separators.)
  set(labels ${ARG_LABELS})
  if(ARG_SERIAL AND NOT labels)
    set(labels realtime)
  endif()
  if(ARG_SERIAL OR ARG_LABELS)
    set(props PROPERTIES)
  endif()
  if(ARG_SERIAL)
    list(APPEND props RUN_SERIAL TRUE)
  endif()
  if(labels)
    list(APPEND props LABELS ${labels})
  endif()
  if(ARG_LABELS)
    list(APPEND props TIMEOUT 120)
  endif()
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPENDS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    SEMNAV_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    SEMNAV_BINARY_DIR="${PROJECT_BINARY_DIR}")
  # Test bodies at -O1 (the libraries they call keep the build type's flags):
  # a quarter less compile time for a clean build.
  target_compile_options(${name} PRIVATE $<$<CONFIG:Release>:-O1>)
  if(props)
    # Real-time and ROS tests: a process per test (roscpp starts once per
    # process; timing is measured alone).
    gtest_discover_tests(${name} WORKING_DIRECTORY ${PROJECT_BINARY_DIR} DISCOVERY_TIMEOUT 60 ${props})
  else()
    semnav_add_gtest_suites(${name})
  endif()
endfunction()

# semnav_add_gtest_suites(<target>): one ctest per GoogleTest suite of
# <target>, listed after each link (cmake/SemnavGTestSuites.cmake). Each
# process start loads MRPT's ~300 shared libraries, bound at load (0.4 s of
# CPU): a process per suite rather than per test saves most of that.
function(semnav_add_gtest_suites target)
  set(ctest_file "${CMAKE_CURRENT_BINARY_DIR}/${target}_suites.cmake")
  set(loader "${CMAKE_CURRENT_BINARY_DIR}/${target}_suites_include.cmake")
  add_custom_command(TARGET ${target} POST_BUILD
    COMMAND ${CMAKE_COMMAND} -D TEST_EXECUTABLE=$<TARGET_FILE:${target}>
      -D CTEST_FILE=${ctest_file} -D WORKING_DIRECTORY=${PROJECT_BINARY_DIR}
      -P ${PROJECT_SOURCE_DIR}/cmake/SemnavGTestSuites.cmake
    BYPRODUCTS ${ctest_file} VERBATIM)
  set_property(TARGET ${target} APPEND PROPERTY LINK_DEPENDS
    ${PROJECT_SOURCE_DIR}/cmake/SemnavGTestSuites.cmake)
  file(WRITE ${loader}
    "if(EXISTS [==[${ctest_file}]==])\n"
    "  include([==[${ctest_file}]==])\n"
    "else()\n"
    "  add_test([==[${target}_NOT_BUILT]==] [==[${target}_NOT_BUILT]==])\n"
    "endif()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${loader})
endfunction()
