# Writes a frame with the C++ types, decodes it with the Java types, and checks
# the printed fields. Fails on any mismatch.
execute_process(COMMAND ${WRITER} --file ${WORK}/sample_frame.bin RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "write_sample_frame failed: ${rc}")
endif()
# -XX:-UsePerfData: no /tmp/hsperfdata_<user> (the JVM puts it there whatever TMPDIR says).
execute_process(COMMAND ${JAVA} -XX:-UsePerfData -cp ${CLASSPATH} DecodeCheck ${WORK}/sample_frame.bin
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "Java decode failed (${rc}): ${err}")
endif()
set(expected "camera_id=3 frame_number=4242 num_robots_blue=1 blue0_id=7 blue0_x=1.25")
string(STRIP "${out}" out)
if(NOT out STREQUAL expected)
  message(FATAL_ERROR "Java decoded '${out}', expected '${expected}'")
endif()
message(STATUS "Java decoded: ${out}")
