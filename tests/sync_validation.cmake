# Runs one test binary with Vulkan synchronization validation and fails unless it really ran
# with it and said nothing. ctest sets JADE_VALIDATION=1 and JADE_SYNC_VALIDATION=1 (see
# CMakeLists.txt); the GpuTest fixture already fails a test on any validation message, this
# also catches messages from CLI child processes (which inherit the environment) and a layer
# that was silently not enabled.
#   cmake -DBINARY=path/to/test_x -DFILTER=gtest-filter -P sync_validation.cmake
execute_process(COMMAND "${BINARY}" "--gtest_filter=${FILTER}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${BINARY} exited with ${rc}")
endif()
if(NOT out MATCHES "jade: Vulkan synchronization validation on")
  message(FATAL_ERROR "synchronization validation was not enabled (no 'synchronization validation on' line)")
endif()
if(out MATCHES "jade: vulkan validation")
  message(FATAL_ERROR "the validation layer reported messages (lines 'jade: vulkan validation ...' above)")
endif()
if(NOT out MATCHES "\\[  PASSED  \\] [1-9]")
  message(FATAL_ERROR "no test ran: filter '${FILTER}' matches nothing")
endif()
