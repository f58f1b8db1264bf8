# Drives kdswap-gui under Xvfb with tests/gui/interaction.script (synthetic mouse and keyboard
# input), then checks the effects from the state dump and checkpoint pictures.
# Called by CTest with -DXVFB_RUN= -DGUI= -DCHECK= -DOUT= (see ui/CMakeLists.txt).
include(${CMAKE_CURRENT_LIST_DIR}/fps_report.cmake)
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
set(state ${OUT}/state.json)
set(fps ${OUT}/fps.json)
set(command ${XVFB_RUN} -a -s "-screen 0 1600x1000x24" ${GUI} --dataset phantom:64 --nodes 8
            --script ${CMAKE_CURRENT_LIST_DIR}/interaction.script --dump-state ${state}
            --screenshot ${OUT}/final.png --report-fps ${fps})
execute_process(COMMAND ${command} RESULT_VARIABLE result)
string(REPLACE ";" " " shown "${command}")
if(NOT result EQUAL 0)
  message(FATAL_ERROR "kdswap-gui exited with ${result}; reproduce with:\n  ${shown}")
endif()
execute_process(COMMAND ${CHECK} ${state} RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "interaction check failed; the pictures of each checkpoint are in ${OUT}; reproduce with:\n  ${shown}")
endif()
kdswap_check_fps_report(${fps} "scripted interaction")
