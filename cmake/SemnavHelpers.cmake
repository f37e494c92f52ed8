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
  gtest_discover_tests(${name} WORKING_DIRECTORY ${PROJECT_BINARY_DIR} DISCOVERY_TIMEOUT 60 ${props})
endfunction()
