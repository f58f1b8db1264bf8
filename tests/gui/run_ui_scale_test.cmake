# kdswap-gui at --ui-scale 2 on a 1600x1000 screen: the window, 3200x2000 at that scale, is cut to
# the screen (1600 wide, 1000 less a title bar's 40 high); the font is twice its size; and the
# viewport and the 8 x 4 stages grid still show their content. Called by CTest with -DXVFB_RUN=
# -DGUI= -DCHECK= -DOUT= (see ui/CMakeLists.txt).
include(${CMAKE_CURRENT_LIST_DIR}/gui_run.cmake)
file(MAKE_DIRECTORY ${OUT})
set(shot ${OUT}/shot.png)
set(layout ${OUT}/layout.json)
file(REMOVE ${shot} ${layout})
gui_run_ok(${OUT} "--ui-scale 2" --dataset phantom:64 --nodes 8 --ui-scale 2 --screenshot ${shot} --layout ${layout}
           --frames 30)
execute_process(COMMAND ${CHECK} ${shot} ${layout} 8 4 RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "screenshot check at --ui-scale 2 failed; look at ${shot} (layout in ${layout})")
endif()
file(READ ${layout} json)
string(JSON width GET "${json}" window width)
string(JSON height GET "${json}" window height)
string(JSON scale GET "${json}" window ui_scale)
string(JSON font GET "${json}" window font_px)
if(NOT width EQUAL 1600 OR NOT height EQUAL 960)
  message(FATAL_ERROR "window ${width}x${height} at --ui-scale 2 on a 1600x1000 screen, expected 1600x960")
endif()
if(NOT scale EQUAL 2 OR NOT font EQUAL 30)
  message(FATAL_ERROR "ui_scale ${scale}, font ${font} px: expected 2 and 30 (twice 15)")
endif()
