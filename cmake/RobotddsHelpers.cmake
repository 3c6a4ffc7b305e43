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

# Install layout. runtime/share_dir.hpp finds an installed share dir as
# <dir of the executable>/../share/robodds, so these two are fixed (not GNUInstallDirs cache
# variables a packager could move apart).
set(ROBODDS_INSTALL_BIN_DIR bin)
set(ROBODDS_INSTALL_SHARE_DIR share/robodds)

# robodds_install_share(FILES f...)
# Installs files of the calling folder into the share dir at their path relative to the
# repository root, which is where the runtime looks for them: e.g. config/pf_estimator.params.yaml
# called from components/pf_estimator goes to share/robodds/components/pf_estimator/config/.
# Install component "runtime" (what the Debian package holds).
function(robodds_install_share)
  cmake_parse_arguments(ARG "" "" "FILES" ${ARGN})
  if(ARG_UNPARSED_ARGUMENTS OR NOT ARG_FILES)
    message(FATAL_ERROR "robodds_install_share: expected FILES f..., got: ${ARGN}")
  endif()
  foreach(file IN LISTS ARG_FILES)
    get_filename_component(absolute "${file}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    if(NOT EXISTS "${absolute}")
      message(FATAL_ERROR "robodds_install_share: ${absolute} does not exist")
    endif()
    file(RELATIVE_PATH relative "${PROJECT_SOURCE_DIR}" "${absolute}")
    get_filename_component(relative_dir "${relative}" DIRECTORY)
    install(FILES "${absolute}" DESTINATION "${ROBODDS_INSTALL_SHARE_DIR}/${relative_dir}" COMPONENT runtime)
  endforeach()
endfunction()
