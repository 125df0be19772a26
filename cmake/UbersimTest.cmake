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
