# kdswap-gui started on data that will not open: a script's `wait full` fails at once with the
# data's error and exit code 2, rather than waiting out its 300 s timeout for a frame that cannot
# come; without a script, --frames also ends with 2; opening other data from the panel then shows
# it and clears the error. Called by CTest with -DXVFB_RUN= -DGUI= -DOUT= (see ui/CMakeLists.txt).
include(${CMAKE_CURRENT_LIST_DIR}/gui_run.cmake)
file(MAKE_DIRECTORY ${OUT})
# A valid header whose sizes no machine holds (the data file exists, so the size is what fails).
file(WRITE ${OUT}/huge.raw "0123456789abcdef")
file(WRITE ${OUT}/huge.nhdr "NRRD0004\ntype: float\ndimension: 3\nsizes: 100000 100000 100000\nendian: little\nencoding: raw\ndata file: huge.raw\n")
file(WRITE ${OUT}/wait.script "wait full\n")
set(expected "huge.nhdr: dimensions 100000x100000x100000 need")

string(TIMESTAMP started "%s")
gui_run_reporting_exit(${OUT} err --volume huge.nhdr --script wait.script --screenshot ${OUT}/shot.png)
string(TIMESTAMP ended "%s")
math(EXPR seconds "${ended} - ${started}")
if(NOT err MATCHES "kdswap-gui exited with 2\n" OR NOT err MATCHES "wait.script:1: wait: no frame will come: ${expected}")
  message(FATAL_ERROR "wait full on data that will not open: expected exit 2 naming the data's error, got: ${err}")
endif()
if(seconds GREATER 120)
  message(FATAL_ERROR "wait full on data that will not open took ${seconds} s: it waited for a frame that cannot come")
endif()

gui_run_reporting_exit(${OUT} err --volume huge.nhdr --frames 5)
if(NOT err MATCHES "kdswap-gui exited with 2\n" OR NOT err MATCHES "${expected}")
  message(FATAL_ERROR "--frames on data that will not open: expected exit 2 naming the data's error, got: ${err}")
endif()

# From there the user opens other data in the Settings panel: it renders, and the error about the
# data before leaves the screen.
file(WRITE ${OUT}/recover.script "frames 3\nmove item data-path\nclick left\ntype phantom:32\nframes 2\nmove item open\nclick left\nwait full\n")
set(state ${OUT}/state.json)
file(REMOVE ${state})
gui_run_ok(${OUT} "opening phantom:32 after data that would not open" --volume huge.nhdr --nodes 4
           --script recover.script --dump-state ${state})
file(READ ${state} json)
string(JSON spec GET "${json}" final data spec)
string(JSON errors LENGTH "${json}" final errors)
if(NOT spec STREQUAL "phantom:32" OR NOT errors EQUAL 0)
  message(FATAL_ERROR "after opening phantom:32: expected it on screen and no error left, the state says ${spec} with ${errors} errors")
endif()
