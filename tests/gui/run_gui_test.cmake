# Runs kdswap-gui under Xvfb for a screenshot and its layout, then checks them.
# Called by CTest with -DXVFB_RUN= -DGUI= -DCHECK= -DOUT= (see ui/CMakeLists.txt).
file(MAKE_DIRECTORY ${OUT})
set(shot ${OUT}/shot.png)
set(layout ${OUT}/layout.json)
file(REMOVE ${shot} ${layout})
set(command ${XVFB_RUN} -a -s "-screen 0 1600x1000x24" ${GUI} --dataset phantom:64 --nodes 8
            --screenshot ${shot} --layout ${layout} --frames 30)
execute_process(COMMAND ${command} RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  string(REPLACE ";" " " shown "${command}")
  message(FATAL_ERROR "kdswap-gui exited with ${result}; reproduce with:\n  ${shown}")
endif()
execute_process(COMMAND ${CHECK} ${shot} ${layout} 8 4 RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "screenshot check failed; look at ${shot} (layout in ${layout})")
endif()
