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

# robodds_unit_test_target(NAME SOURCES s... [DEPS d...]): an executable compiled and linked as every
# unit test is (GoogleTest, the warnings, the test sources at -O1). Used by robodds_unit_test() and by
# the owner of the unit tests' precompiled header, so that the two cannot drift apart: GCC uses a
# precompiled header only when the compile flags that matter (-fPIE, the macros it reads) are the same.
function(robodds_unit_test_target name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main GTest::gmock robodds_warnings)
  # The test's own sources at -O1 (the last -O wins): they were 45 % of a clean build's compile
  # time, and -O3 buys them nothing, since the code under test comes from the libraries, built as
  # configured. -O1 compiles a test file in two thirds of the time (runtime/host/test/host_test.cpp:
  # 9.0 s -> 6.0 s), which keeps scripts/test.sh within its 30 minutes on 2 cores.
  target_compile_options(${name} PRIVATE $<$<CONFIG:Release>:-O1>)
endfunction()

# robodds_unit_test_pch(): with ROBODDS_UNIT_TEST_PCH, the target robodds_unit_test_pch compiles
# <gtest/gtest.h> once into a precompiled header that every robodds_unit_test() reuses
# (REUSE_FROM) instead of parsing it again. Only gtest: every test file includes it, while Eigen is
# read by 37 of the 212 test files and gmock by 5, and a bigger header costs every test file more
# to load (docs/performance.md, Build time). It is force-included first into every test file: keep
# it to third-party headers that change nothing by being read first, and never Fast DDS (only
# runtime/dds/ may include it: tests/layering/). GCC uses it only when the flags that matter
# (-fPIE, the macros it reads) are the tests' own: the owner is made by robodds_unit_test_target(),
# and -Winvalid-pch (added by CMake) with -Werror fails the build if GCC could not use it.
# Call it once, after find_package(GTest).
function(robodds_unit_test_pch)
  if(NOT ROBODDS_UNIT_TEST_PCH)
    return()
  endif()
  robodds_unit_test_target(robodds_unit_test_pch SOURCES ${PROJECT_SOURCE_DIR}/cmake/unit_test_pch.cpp)
  target_precompile_headers(robodds_unit_test_pch PRIVATE <gtest/gtest.h>)
endfunction()

# robodds_unit_test(NAME SOURCES s... [DEPS d...] [READS_SOURCE_TREE])
# A GoogleTest executable; every TEST becomes its own ctest entry (label "unit").
# READS_SOURCE_TREE: the test reads checked-in files (docs, XML, defaults files) from
# ROBODDS_SOURCE_DIR, defined as the repository root.
function(robodds_unit_test name)
  if(NOT ROBODDS_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "READS_SOURCE_TREE" "" "SOURCES;DEPS" ${ARGN})
  robodds_unit_test_target(${name} SOURCES ${ARG_SOURCES} DEPS ${ARG_DEPS})
  if(ROBODDS_UNIT_TEST_PCH)
    target_precompile_headers(${name} REUSE_FROM robodds_unit_test_pch)
  endif()
  if(ARG_READS_SOURCE_TREE)
    target_compile_definitions(${name} PRIVATE ROBODDS_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  endif()
  # TempDir() of every case is the build tree's test_tmp/, not /tmp: two checkouts testing on one
  # machine never share a case's files, and nothing is left in /tmp.
  file(MAKE_DIRECTORY "${PROJECT_BINARY_DIR}/test_tmp")
  gtest_discover_tests(${name} TEST_PREFIX "${name}." DISCOVERY_MODE PRE_TEST
                       PROPERTIES LABELS unit ENVIRONMENT "TEST_TMPDIR=${PROJECT_BINARY_DIR}/test_tmp/")
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

# Install layout. runtime/config/share_dir.hpp finds an installed share dir as
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

# robodds_component(NAME type [LIBRARY target] NODE_SOURCES s... [DEPS d...] [NODE_TESTS t...])
# A component type, registered from its own folder: builds the node library LIBRARY (default
# robodds_<type>_node; it links robodds_runtime_core) and adds the type to the set that
# robodds_registered_components_library() registers. Each NODE_TESTS file is a unit test of the
# node on the in-memory bus (runtime/testing/node_harness.hpp), named after the file. The node
# sources must contain ROBODDS_REGISTER_COMPONENT(type, ...) (runtime/component/registry.hpp) with the same
# type name; config/<type>.params.yaml (the generated defaults file) is installed into the share dir.
# Nothing happens without the DDS runtime (-DROBODDS_WITH_DDS=OFF).
function(robodds_component)
  cmake_parse_arguments(ARG "" "NAME;LIBRARY" "NODE_SOURCES;DEPS;NODE_TESTS" ${ARGN})
  if(NOT ARG_NAME MATCHES "^[a-z][a-z0-9_]*$")
    message(FATAL_ERROR "robodds_component: NAME '${ARG_NAME}' must be a lower-case identifier (the scenario's component type)")
  endif()
  if(NOT ARG_NODE_SOURCES)
    message(FATAL_ERROR "robodds_component(${ARG_NAME}): NODE_SOURCES is empty")
  endif()
  if(NOT ROBODDS_WITH_DDS)
    return()
  endif()
  get_property(registered GLOBAL PROPERTY ROBODDS_COMPONENTS)
  if(ARG_NAME IN_LIST registered)
    get_property(first GLOBAL PROPERTY ROBODDS_COMPONENT_DIR_${ARG_NAME})
    message(FATAL_ERROR "robodds_component: component type '${ARG_NAME}' is already registered in ${first}")
  endif()
  if(NOT ARG_LIBRARY)
    set(ARG_LIBRARY robodds_${ARG_NAME}_node)
  endif()
  # robodds_system: the runtime with the robot system's topics, sample checks and shared facts.
  robodds_library(${ARG_LIBRARY} SOURCES ${ARG_NODE_SOURCES} DEPS ${ARG_DEPS} robodds_system)
  # The documented defaults file, by convention config/<type>.params.yaml of this folder, relative
  # to the repository root / share dir: ROBODDS_REGISTER_COMPONENT registers this path.
  file(RELATIVE_PATH defaults_file ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR}/config/${ARG_NAME}.params.yaml)
  target_compile_definitions(${ARG_LIBRARY} PRIVATE ROBODDS_COMPONENT_DEFAULTS_FILE="${defaults_file}")
  set_property(GLOBAL APPEND PROPERTY ROBODDS_COMPONENTS ${ARG_NAME})
  set_property(GLOBAL PROPERTY ROBODDS_COMPONENT_LIBRARY_${ARG_NAME} ${ARG_LIBRARY})
  set_property(GLOBAL PROPERTY ROBODDS_COMPONENT_DIR_${ARG_NAME} ${CMAKE_CURRENT_SOURCE_DIR})
  if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/config/${ARG_NAME}.params.yaml)
    robodds_install_share(FILES config/${ARG_NAME}.params.yaml)
  else()
    # A new component: its defaults file is generated from its parameter table once it builds
    # (scripts/regenerate_params.sh); until then the drift test fails and says so.
    message(WARNING "robodds_component(${ARG_NAME}): ${defaults_file} does not exist yet: build, then run scripts/regenerate_params.sh")
  endif()
  robodds_component_executable(${ARG_NAME} ${ARG_LIBRARY})
  foreach(test_source IN LISTS ARG_NODE_TESTS)
    get_filename_component(test_name ${test_source} NAME_WE)
    robodds_unit_test(${test_name} SOURCES ${test_source} DEPS ${ARG_LIBRARY} robodds_node_harness)
  endforeach()
endfunction()

# robodds_component_executable(TYPE NODE_LIBRARY)
# The standalone executable robodds-<type> (underscores become dashes): the generic host with
# this one component, for a robot without a scenario file (tools/component/component_main.hpp).
# Its main is generated into the build tree; it goes to <build>/bin/ and is installed into bin/.
function(robodds_component_executable type node_library)
  string(REPLACE "_" "-" executable "robodds-${type}")
  set(ROBODDS_COMPONENT_TYPE ${type})
  configure_file(${PROJECT_SOURCE_DIR}/cmake/component_main.cpp.in
                 ${CMAKE_CURRENT_BINARY_DIR}/${executable}_main.cpp @ONLY)
  add_executable(${executable} ${CMAKE_CURRENT_BINARY_DIR}/${executable}_main.cpp)
  target_link_libraries(${executable} PRIVATE ${node_library} robodds_component_main robodds_warnings)
  set_target_properties(${executable} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/bin)
  install(TARGETS ${executable} RUNTIME DESTINATION ${ROBODDS_INSTALL_BIN_DIR} COMPONENT runtime)
endfunction()

# robodds_registered_components_library(NAME)
# A static library holding register_builtin_components() (runtime/component/registry.hpp), generated into
# the build tree from every robodds_component() call made so far: it calls each type's
# registration function, sorted by type name so that the registry (and `robodds components`)
# has a fixed order, and links every node library. Call it after the component folders are added.
function(robodds_registered_components_library name)
  get_property(components GLOBAL PROPERTY ROBODDS_COMPONENTS)
  if(NOT components)
    message(FATAL_ERROR "robodds_registered_components_library: no robodds_component() call before it")
  endif()
  list(SORT components)
  set(ROBODDS_COMPONENT_DECLARATIONS "")
  set(ROBODDS_COMPONENT_CALLS "")
  set(libraries "")
  foreach(component IN LISTS components)
    string(APPEND ROBODDS_COMPONENT_DECLARATIONS "void register_${component}(ComponentRegistry& registry);\n")
    string(APPEND ROBODDS_COMPONENT_CALLS "  component_registration::register_${component}(registry);\n")
    get_property(library GLOBAL PROPERTY ROBODDS_COMPONENT_LIBRARY_${component})
    list(APPEND libraries ${library})
  endforeach()
  configure_file(${PROJECT_SOURCE_DIR}/cmake/registered_components.cpp.in
                 ${CMAKE_CURRENT_BINARY_DIR}/registered_components.cpp @ONLY)
  robodds_library(${name} SOURCES ${CMAKE_CURRENT_BINARY_DIR}/registered_components.cpp DEPS robodds_system ${libraries})
endfunction()

# robodds_metrics_module(NAME kind SOURCES s... [DEPS d...] [TESTS t...])
# A metrics module of the evaluator (sim/evaluator/module/metrics_module.hpp), registered from its
# own folder like a component: builds robodds_<kind>_metrics_module and adds the module to the set
# that robodds_registered_metrics_modules_library() registers. The sources must contain
# ROBODDS_REGISTER_METRICS_MODULE(kind, ...) with the same name; it registers this folder. Each
# TESTS file is a unit test named evaluator_<file name>, on the in-memory bus with the whole
# evaluator. Nothing happens without the DDS runtime (-DROBODDS_WITH_DDS=OFF).
function(robodds_metrics_module)
  cmake_parse_arguments(ARG "" "NAME" "SOURCES;DEPS;TESTS" ${ARGN})
  if(NOT ARG_NAME MATCHES "^[a-z][a-z0-9_]*$" OR NOT ARG_SOURCES)
    message(FATAL_ERROR "robodds_metrics_module: expected NAME <lower-case identifier> SOURCES s..., got: ${ARGN}")
  endif()
  if(NOT ROBODDS_WITH_DDS)
    return()
  endif()
  set(library robodds_${ARG_NAME}_metrics_module)
  robodds_library(${library} SOURCES ${ARG_SOURCES} DEPS ${ARG_DEPS} robodds_evaluator_module)
  # The module's folder, relative to the repository root: ROBODDS_REGISTER_METRICS_MODULE registers it.
  file(RELATIVE_PATH folder ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_definitions(${library} PRIVATE ROBODDS_METRICS_MODULE_FOLDER="${folder}")
  set_property(GLOBAL APPEND PROPERTY ROBODDS_METRICS_MODULES ${ARG_NAME})
  foreach(test_source IN LISTS ARG_TESTS)
    get_filename_component(test_name ${test_source} NAME_WE)
    robodds_unit_test(evaluator_${test_name} SOURCES ${test_source} DEPS robodds_evaluator_node robodds_node_harness)
  endforeach()
endfunction()

# robodds_registered_metrics_modules_library(NAME)
# A static library holding register_builtin_metrics_modules() (metrics_module_registry.hpp),
# generated into the build tree from every robodds_metrics_module() call made so far, sorted by
# name, and linking every module library. Call it after the module folders are added.
function(robodds_registered_metrics_modules_library name)
  get_property(modules GLOBAL PROPERTY ROBODDS_METRICS_MODULES)
  list(SORT modules)
  set(ROBODDS_METRICS_MODULE_DECLARATIONS "")
  set(ROBODDS_METRICS_MODULE_CALLS "")
  set(libraries "")
  foreach(module IN LISTS modules)
    string(APPEND ROBODDS_METRICS_MODULE_DECLARATIONS "void register_${module}(evaluator::MetricsModuleRegistry& registry);\n")
    string(APPEND ROBODDS_METRICS_MODULE_CALLS "  metrics_module_registration::register_${module}(registry);\n")
    list(APPEND libraries robodds_${module}_metrics_module)
  endforeach()
  configure_file(${PROJECT_SOURCE_DIR}/cmake/registered_metrics_modules.cpp.in
                 ${CMAKE_CURRENT_BINARY_DIR}/registered_metrics_modules.cpp @ONLY)
  robodds_library(${name} SOURCES ${CMAKE_CURRENT_BINARY_DIR}/registered_metrics_modules.cpp DEPS robodds_evaluator_module ${libraries})
endfunction()
