# Runs `dualcontact PRM` in an empty WORKDIR.
#  MODE=compare: must succeed; WORKDIR/<output>/results.txt is compared with
#                REF by numdiff (relative 1e-8, absolute 1e-12), where <output>
#                is the only folder the run created.
#  MODE=fail:    must exit non-zero, print EXPECT (stdout or stderr), and leave
#                WORKDIR empty (no partial output).
file(REMOVE_RECURSE ${WORKDIR})
file(MAKE_DIRECTORY ${WORKDIR})
execute_process(COMMAND ${APP} ${PRM} ${EXTRA_ARGS}
  WORKING_DIRECTORY ${WORKDIR}
  RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _err)
message("${_out}")
message("${_err}")
if(MODE STREQUAL "fail")
  if(_rc EQUAL 0)
    message(FATAL_ERROR "expected a failure, but the run exited with 0")
  endif()
  string(FIND "${_out}${_err}" "${EXPECT}" _pos)
  if(_pos EQUAL -1)
    message(FATAL_ERROR "the message does not contain the expected text: ${EXPECT}")
  endif()
  file(GLOB_RECURSE _left ${WORKDIR}/*)
  file(GLOB _left_dirs LIST_DIRECTORIES true ${WORKDIR}/*)
  if(_left OR _left_dirs)
    message(FATAL_ERROR "a failed run left output behind: ${_left} ${_left_dirs}")
  endif()
else()
  if(NOT _rc EQUAL 0)
    message(FATAL_ERROR "the run failed with exit code ${_rc}")
  endif()
  file(GLOB_RECURSE _results ${WORKDIR}/*results.txt)
  list(LENGTH _results _n)
  if(NOT _n EQUAL 1)
    message(FATAL_ERROR "expected exactly one results.txt, found: ${_results}")
  endif()
  execute_process(COMMAND ${NUMDIFF} -q -s " \t\n=," -r 1e-8 -a 1e-12 ${_results} ${REF}
    RESULT_VARIABLE _diff_rc OUTPUT_VARIABLE _diff_out)
  if(NOT _diff_rc EQUAL 0)
    execute_process(COMMAND ${NUMDIFF} -s " \t\n=," -r 1e-8 -a 1e-12 ${_results} ${REF})
    message(FATAL_ERROR "results differ from ${REF}")
  endif()
endif()
