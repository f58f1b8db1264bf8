# kdswap-gui opens a headerless .raw file with the --raw-* options, and without them says which
# options are missing. The file comes by --volume (as in `kdswap render`), then by --dataset, which
# the app also takes files in; --up sets the view's up axis. Called by CTest with -DXVFB_RUN= -DGUI=
# -DOUT= (see ui/CMakeLists.txt).
include(${CMAKE_CURRENT_LIST_DIR}/gui_run.cmake)
file(MAKE_DIRECTORY ${OUT})
# 8 x 8 x 8 uint8 voxels whose name gives no layout: 512 bytes of text make a varying volume.
string(REPEAT "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdef" 16 voxels)
file(WRITE ${OUT}/scan.raw "${voxels}")
set(state ${OUT}/state.json)
file(REMOVE ${state})
gui_run_ok(${OUT} "scan.raw with its layout" --volume scan.raw --raw-dims 8x8x8 --raw-type uint8 --up -y --nodes 4
           --screenshot ${OUT}/shot.png --frames 5 --dump-state ${state})
file(READ ${state} json)
string(JSON spec GET "${json}" final data spec)
string(JSON type GET "${json}" final data type)
string(JSON dims GET "${json}" final data dims)
string(REGEX REPLACE "[ \n\t]" "" dims "${dims}")
if(NOT spec STREQUAL "scan.raw" OR NOT type STREQUAL "uint8" OR NOT dims STREQUAL "[8,8,8]")
  message(FATAL_ERROR "expected scan.raw as 8x8x8 uint8 on screen, the state says ${spec} ${dims} ${type}")
endif()
string(JSON up GET "${json}" final view up)
if(NOT up STREQUAL "-y")
  message(FATAL_ERROR "--up -y: the state's view has up ${up}")
endif()

# Without the layout: one line naming the options, exit code 2.
gui_run_reporting_exit(${OUT} err --dataset scan.raw --screenshot ${OUT}/none.png --frames 5)
if(NOT err MATCHES "kdswap-gui exited with 2\n" OR
   NOT err MATCHES "scan.raw: raw file layout unknown: give --raw-dims WxHxD and --raw-type TYPE")
  message(FATAL_ERROR "a raw file without layout: expected exit 2 naming --raw-dims and --raw-type, got: ${err}")
endif()
