# robodds_generate_idl(TARGET_NAME IDL_FILE)
# Runs fastddsgen at build time into the build tree and builds two libraries:
#   ${TARGET_NAME}            the plain C++ types (Fast CDR only; safe to include anywhere)
#   ${TARGET_NAME}_typesupport the TopicDataType classes (Fast DDS; linked by runtime/ only)
# plus ${TARGET_NAME}_visit.hpp: generated field visitors (printing, CSV, finiteness checks), and
# ${TARGET_NAME}_enums.hpp: the IDL names of enum values (enum_name()).
find_program(FASTDDSGEN_EXECUTABLE fastddsgen REQUIRED)
find_package(Python3 REQUIRED COMPONENTS Interpreter)

function(robodds_generate_idl target idl_file)
  get_filename_component(idl_abs ${idl_file} ABSOLUTE)
  get_filename_component(stem ${idl_file} NAME_WE)
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/generated/robodds/idl)
  set(gen_sources ${out_dir}/${stem}.cxx ${out_dir}/${stem}.h)
  set(gen_typesupport ${out_dir}/${stem}PubSubTypes.cxx ${out_dir}/${stem}PubSubTypes.h)
  set(gen_visit ${out_dir}/${stem}_visit.hpp)
  set(gen_enums ${out_dir}/${stem}_enums.hpp)
  # fastddsgen preprocesses the IDL into <temp dir>/<idl file name>.cc, by default /tmp/ for every
  # build on the machine. Two builds generating at once (fresh build dirs) could read each other's
  # file: half-written, fastddsgen fails ("mismatched input '<EOF>'", no file written); whole, from
  # another checkout, it succeeds with a robodds.h without any type (the file's line markers name
  # the other checkout's IDL) and no PubSubTypes files: the compiles fail ("'SampleHeader' does
  # not name a type" in robodds_visit.hpp), the next build regenerates and passes. -t: our own file.
  set(tmp_dir ${CMAKE_CURRENT_BINARY_DIR}/fastddsgen_tmp/${target})
  add_custom_command(
    OUTPUT ${gen_sources} ${gen_typesupport}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${out_dir} ${tmp_dir}
    # No -typeobject: the type support announces no TypeObject (XCDR1 interop with other vendors).
    COMMAND ${FASTDDSGEN_EXECUTABLE} -replace -t ${tmp_dir} -d ${out_dir} ${idl_abs}
    DEPENDS ${idl_abs}
    COMMENT "fastddsgen ${stem}.idl"
    VERBATIM)
  add_custom_command(
    OUTPUT ${gen_visit} ${gen_enums}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${out_dir}
    COMMAND Python3::Interpreter ${PROJECT_SOURCE_DIR}/cmake/idl_visitors.py ${idl_abs} ${gen_visit} ${gen_enums}
    DEPENDS ${idl_abs} ${PROJECT_SOURCE_DIR}/cmake/idl_visitors.py
    COMMENT "field visitors for ${stem}.idl"
    VERBATIM)

  add_library(${target} STATIC ${gen_sources} ${gen_visit} ${gen_enums})
  target_include_directories(${target} SYSTEM PUBLIC ${CMAKE_CURRENT_BINARY_DIR}/generated)
  target_link_libraries(${target} PUBLIC fastcdr)
  # fixed_size_string.hpp (header only) comes from the Fast RTPS include directory.
  target_include_directories(${target} SYSTEM PUBLIC $<TARGET_PROPERTY:fastrtps,INTERFACE_INCLUDE_DIRECTORIES>)

  add_library(${target}_typesupport STATIC ${gen_typesupport})
  target_link_libraries(${target}_typesupport PUBLIC ${target} fastrtps)
endfunction()
