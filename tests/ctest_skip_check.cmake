# Runs CTest on three tags of ctest_skip_probe, registered with the skip
# properties every rsl test gets, and requires the mixed tag (one failing,
# one skipping case) to fail: a skip must never hide a failure.
# -DCTEST=<ctest> -DPROBE=<exe> -DWORK_DIR=<dir> -DSKIP_PROPERTIES="<properties>" [-DWRAPPER="a|b|c"]
foreach(var CTEST PROBE WORK_DIR SKIP_PROPERTIES)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "ctest_skip_check.cmake: -D${var}= is missing")
  endif()
endforeach()
set(wrapper_args "")
if(WRAPPER)
  string(REPLACE "|" ";" wrapper_list "${WRAPPER}")
  foreach(arg IN LISTS wrapper_list)
    string(APPEND wrapper_args " [==[${arg}]==]")
  endforeach()
endif()
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(testfile "")
foreach(tag mixed skip-only pass-only)
  string(APPEND testfile
    "add_test(${tag}${wrapper_args} [==[${PROBE}]==] [==[[${tag}]]==])\n"
    "set_tests_properties(${tag} PROPERTIES ${SKIP_PROPERTIES})\n")
endforeach()
file(WRITE "${WORK_DIR}/CTestTestfile.cmake" "${testfile}")
execute_process(COMMAND "${CTEST}" --output-on-failure
  WORKING_DIRECTORY "${WORK_DIR}" RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(expected
  "mixed [.]+[*]+Failed"
  "skip-only [.]+[*]+Skipped"
  "pass-only [.]+ +Passed")
foreach(pattern IN LISTS expected)
  if(NOT out MATCHES "${pattern}")
    message(FATAL_ERROR "ctest_skip_check.cmake: CTest's output lacks '${pattern}' (exit ${code}):\n${out}${err}")
  endif()
endforeach()
if(code EQUAL 0)
  message(FATAL_ERROR "ctest_skip_check.cmake: CTest exited 0 although the mixed tag fails:\n${out}")
endif()
message(STATUS "CTest failed the mixed tag, skipped the skip-only tag and passed the pass-only tag")
