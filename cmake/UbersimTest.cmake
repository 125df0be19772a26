# ubersim_add_test(NAME name COMMAND program args...): add_test, with the
# command run by tests/support/own_tmpdir.sh, so that TMPDIR is a folder of
# the test's own under the TMPDIR ctest runs with: removed when the test
# passes, kept and named when it fails. Every test is added through it (C++
# tests through ubersim_add_gtest). A target as program stands for its file.
set(UBERSIM_OWN_TMPDIR ${CMAKE_SOURCE_DIR}/tests/support/own_tmpdir.sh)

function(ubersim_add_test)
  cmake_parse_arguments(ARG "" "NAME" "COMMAND" ${ARGN})
  list(POP_FRONT ARG_COMMAND program)
  if(TARGET ${program})
    set(program $<TARGET_FILE:${program}>)
  endif()
  add_test(NAME ${ARG_NAME} COMMAND ${UBERSIM_OWN_TMPDIR} ${ARG_NAME} ${program} ${ARG_COMMAND})
endfunction()

# ubersim_add_script_test(NAME name SCRIPT script TIMEOUT seconds [LABELS label]
# [PARALLEL] [SKIPPABLE]): a shell script that runs tools/launch.sh or the
# programs of the build, given the source folder, isolated (tests/run_isolated.sh:
# its own network namespace, or its own port) and told the build
# (UBERSIM_BUILD_DIR). Alone unless PARALLEL; exit 77 is a skip when SKIPPABLE.
# LABELS defaults to e2e.
function(ubersim_add_script_test)
  cmake_parse_arguments(ARG "PARALLEL;SKIPPABLE" "NAME;SCRIPT;TIMEOUT;LABELS" "" ${ARGN})
  if(NOT ARG_LABELS)
    set(ARG_LABELS e2e)
  endif()
  ubersim_add_test(NAME ${ARG_NAME}
    COMMAND ${UBERSIM_RUN_ISOLATED} ${ARG_NAME} ${ARG_SCRIPT} ${CMAKE_SOURCE_DIR})
  set_tests_properties(${ARG_NAME} PROPERTIES LABELS ${ARG_LABELS} TIMEOUT ${ARG_TIMEOUT}
    ENVIRONMENT UBERSIM_BUILD_DIR=${CMAKE_BINARY_DIR})
  if(NOT ARG_PARALLEL)
    set_tests_properties(${ARG_NAME} PROPERTIES RUN_SERIAL TRUE)
  endif()
  if(ARG_SKIPPABLE)
    set_tests_properties(${ARG_NAME} PROPERTIES SKIP_RETURN_CODE 77)
  endif()
endfunction()
