# kdswap-gui, started on phantom:32, opens a headerless .raw file typed into its data panel with the
# layout set in the panel's fields (tests/gui/raw_panel.script); a wrong layout first shows the
# reader's error and the app goes on. Called by CTest with -DXVFB_RUN= -DGUI= -DOUT= (see
# ui/CMakeLists.txt).
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
# A 16-byte header, then 8 x 6 x 4 uint16 voxels, big-endian: bytes "A" "a".."h" are the values
# 0x4161..0x4168 (16737..16744); read little-endian they would be 24897 or more. CMake writes no
# zero bytes, hence letters.
string(REPEAT "AaAbAcAdAeAfAgAh" 24 voxels)
file(WRITE ${OUT}/panel.raw "HEADER-16-BYTES-${voxels}")
set(state ${OUT}/state.json)
set(command ${XVFB_RUN} -a -s "-screen 0 1600x1000x24" ${GUI} --dataset phantom:32 --nodes 4
            --script ${CMAKE_CURRENT_LIST_DIR}/raw_panel.script --dump-state ${state} --screenshot ${OUT}/final.png)
execute_process(COMMAND ${command} WORKING_DIRECTORY ${OUT} RESULT_VARIABLE result ERROR_VARIABLE err)
string(REPLACE ";" " " shown "${command}")
set(reproduce "the window at each checkpoint is in ${OUT}; reproduce (in ${OUT}) with:\n  ${shown}")
if(NOT result EQUAL 0)
  message(FATAL_ERROR "kdswap-gui exited with ${result}: ${err}\n${reproduce}")
endif()
file(READ ${state} json)

# The wrong layout: the reader's one-line error in the window, phantom:32 still on screen.
string(JSON refused GET "${json}" checkpoints refused data spec)
string(JSON errors GET "${json}" checkpoints refused errors)
if(NOT refused STREQUAL "phantom:32" OR NOT errors MATCHES "panel.raw: truncated: 8x6x5 uint16 needs 480 bytes from byte 16, the file has 400")
  message(FATAL_ERROR "a layout too big for panel.raw: expected its size error with phantom:32 still shown, the state "
                      "says ${refused} and errors ${errors}\n${reproduce}")
endif()

# The right layout: every field used.
string(JSON spec GET "${json}" final data spec)
string(JSON type GET "${json}" final data type)
string(JSON dims GET "${json}" final data dims)
string(JSON spacing GET "${json}" final data spacing)
string(JSON low GET "${json}" final data range 0)
string(JSON high GET "${json}" final data range 1)
string(REGEX REPLACE "\\.0$" "" low "${low}")
string(REGEX REPLACE "\\.0$" "" high "${high}")
string(REGEX REPLACE "[ \n\t]" "" dims "${dims}")
string(REGEX REPLACE "[ \n\t]|\\.0" "" spacing "${spacing}")
if(NOT spec STREQUAL "panel.raw" OR NOT type STREQUAL "uint16" OR NOT dims STREQUAL "[8,6,4]" OR NOT spacing STREQUAL "[1,1,2]")
  message(FATAL_ERROR "expected panel.raw as 8x6x4 uint16 with spacing 1,1,2 on screen, the state says ${spec} "
                      "${dims} ${type} spacing ${spacing}\n${reproduce}")
endif()
if(NOT low EQUAL 16737 OR NOT high EQUAL 16744)
  message(FATAL_ERROR "panel.raw read big-endian after 16 header bytes has values 16737..16744, the state says "
                      "${low}..${high}\n${reproduce}")
endif()
