# ubersim_generate_lcm_types(TARGET name JAR jar_target FILES a.lcm b.lcm ...)
# Runs lcm-gen at build time: C++ headers behind an INTERFACE library TARGET,
# and (when Java is present) Java classes packed into ${JAR}.jar for lcm-spy.
function(ubersim_generate_lcm_types)
  cmake_parse_arguments(ARG "" "TARGET;JAR" "FILES" ${ARGN})
  set(cpp_dir ${CMAKE_CURRENT_BINARY_DIR}/cpp)
  set(java_dir ${CMAKE_CURRENT_BINARY_DIR}/java)
  set(headers "")
  set(java_sources "")
  foreach(lcm_file ${ARG_FILES})
    get_filename_component(type_name ${lcm_file} NAME_WE)
    list(APPEND headers ${cpp_dir}/ubersim/${type_name}.hpp)
    list(APPEND java_sources ${java_dir}/ubersim/${type_name}.java)
  endforeach()
  list(TRANSFORM ARG_FILES PREPEND ${CMAKE_CURRENT_SOURCE_DIR}/ OUTPUT_VARIABLE lcm_paths)

  add_custom_command(
    OUTPUT ${headers}
    COMMAND ${LCM_GEN_EXECUTABLE} --cpp --cpp-hpath ${cpp_dir} ${lcm_paths}
    DEPENDS ${lcm_paths}
    COMMENT "lcm-gen: C++ message types"
    VERBATIM)
  # Headers generated from the .lcm files by our own scripts (one parser,
  # lcm_schema.py): encoded_bounds.hpp, the bounds every decode checks first,
  # and lcm_fields.hpp, every field by its path (see each gen_<name>.py for why).
  set(generated_headers "")
  foreach(name encoded_bounds lcm_fields)
    set(header ${cpp_dir}/ubersim/${name}.hpp)
    set(generator ${CMAKE_CURRENT_SOURCE_DIR}/gen_${name}.py)
    add_custom_command(
      OUTPUT ${header}
      COMMAND ${Python3_EXECUTABLE} ${generator} ${header} ${lcm_paths}
      DEPENDS ${lcm_paths} ${generator} ${CMAKE_CURRENT_SOURCE_DIR}/lcm_schema.py ${headers}
      COMMENT "${name}.hpp from the LCM message types"
      VERBATIM)
    list(APPEND generated_headers ${header})
  endforeach()
  add_custom_target(${ARG_TARGET}_gen DEPENDS ${headers} ${generated_headers})
  add_library(${ARG_TARGET} INTERFACE)
  add_dependencies(${ARG_TARGET} ${ARG_TARGET}_gen)
  target_include_directories(${ARG_TARGET} SYSTEM INTERFACE ${cpp_dir})
  target_link_libraries(${ARG_TARGET} INTERFACE ubersim::lcm)

  if(UBERSIM_BUILD_JAVA)
    set(jar_file ${CMAKE_CURRENT_BINARY_DIR}/${ARG_JAR}.jar)
    add_custom_command(
      OUTPUT ${jar_file}
      COMMAND ${CMAKE_COMMAND} -E remove_directory ${java_dir}
      COMMAND ${LCM_GEN_EXECUTABLE} --java --jpath ${java_dir} ${lcm_paths}
      COMMAND ${Java_JAVAC_EXECUTABLE} -nowarn -cp ${LCM_JAR} -d ${java_dir}/classes ${java_sources}
      COMMAND ${Java_JAR_EXECUTABLE} cf ${jar_file} -C ${java_dir}/classes .
      DEPENDS ${lcm_paths}
      COMMENT "lcm-gen + javac: ${ARG_JAR}.jar for lcm-spy"
      VERBATIM)
    add_custom_target(${ARG_JAR} ALL DEPENDS ${jar_file})
    set(UBERSIM_TYPES_JAR ${jar_file} CACHE INTERNAL "jar of the ubersim LCM types")
  endif()
endfunction()
