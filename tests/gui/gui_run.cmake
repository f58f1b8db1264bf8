# Running kdswap-gui under Xvfb from a GUI test script (include()d; XVFB_RUN and GUI as the tests get them).

# gui_run_ok(DIR WHAT ARGS...): runs the app with ARGS in DIR; unless it exits 0, stops the test
# with WHAT, the exit code, the app's errors and the command that reproduces it.
function(gui_run_ok dir what)
  set(command ${XVFB_RUN} -a -s "-screen 0 1600x1000x24" ${GUI} ${ARGN})
  execute_process(COMMAND ${command} WORKING_DIRECTORY ${dir} RESULT_VARIABLE result ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    string(REPLACE ";" " " shown "${command}")
    message(FATAL_ERROR "${what}: kdswap-gui exited with ${result}: ${err}\nreproduce (in ${dir}) with:\n  ${shown}")
  endif()
endfunction()

# gui_run_reporting_exit(DIR ERR_VAR ARGS...): runs the app with ARGS in DIR and sets ERR_VAR to
# its errors followed by the line "kdswap-gui exited with N". A shell inside xvfb-run reports the
# code: an app that exits at once may leave xvfb-run failing to remove its temporary directory
# while Xvfb is still starting, and xvfb-run then exits 5 in place of the app's code.
function(gui_run_reporting_exit dir errVar)
  execute_process(COMMAND ${XVFB_RUN} -a -s "-screen 0 1600x1000x24"
                          sh -c "\"$0\" \"$@\"; echo \"kdswap-gui exited with $?\" >&2" ${GUI} ${ARGN}
                  WORKING_DIRECTORY ${dir} ERROR_VARIABLE err)
  set(${errVar} "${err}" PARENT_SCOPE)
endfunction()
