# Small helper functions shared by every target of the project.

# Warnings for all project code (generated code gets none of these).
add_library(robodds_warnings INTERFACE)
target_compile_options(robodds_warnings INTERFACE -Wall -Wextra -Wpedantic
  $<$<BOOL:${ROBODDS_WERROR}>:-Werror>)

# robodds_library(NAME SOURCES s... [DEPS d...])
# A static library whose headers are included by their path from the repository root,
# e.g. #include "components/pf_estimator/particle_filter.hpp".
function(robodds_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} PUBLIC ${ARG_DEPS} PRIVATE robodds_warnings)
endfunction()

# robodds_unit_test(NAME SOURCES s... [DEPS d...])
# A GoogleTest executable; every TEST becomes its own ctest entry (label "unit").
function(robodds_unit_test name)
  if(NOT ROBODDS_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main GTest::gmock robodds_warnings)
  gtest_discover_tests(${name} TEST_PREFIX "${name}." DISCOVERY_MODE PRE_TEST PROPERTIES LABELS unit)
endfunction()

# robodds_benchmark(NAME SOURCES s... [DEPS d...])
function(robodds_benchmark name)
  if(NOT ROBODDS_BUILD_BENCH)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} benchmark::benchmark robodds_warnings)
endfunction()
