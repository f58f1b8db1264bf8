# Command-line mistakes a user makes, and what kdswap answers: exit 2 and one line naming the option
# or file and the problem (STYLE.md's errors), never a silent success or a library's message. Each
# case runs tests/cli_expect.cmake; inputs (plain.raw, bad.json, header.nhdr) are made in WORK.
set(_cliWork ${CMAKE_CURRENT_BINARY_DIR}/cli_option_errors)
set(_tiny --dataset phantom:16 --size 16x16 --out o.png)
set(_benchTiny --dataset phantom:16 --sizes 16 --nodes 1 --frames 1)

# kdswap_cli_case(NAME [PROGRAM target] [CODE n] [EXPECT stderr-regex] [STDOUT regex] [FORBID regex]
#                 ARGS ...). Regexes are CMake's; write '.' for a quote or a semicolon.
function(kdswap_cli_case name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "PROGRAM;CODE;EXPECT;STDOUT;FORBID" "ARGS")
  if(NOT arg_PROGRAM)
    set(arg_PROGRAM kdswap)
  endif()
  set(_cmd $<TARGET_FILE:${arg_PROGRAM}> ${arg_ARGS})
  string(REPLACE ";" "\\;" _cmd "${_cmd}")
  set(_defs)  # the command goes straight into add_test: one more list level would split it
  foreach(_key CODE EXPECT STDOUT FORBID)
    if(DEFINED arg_${_key})
      list(APPEND _defs "-D${_key}=${arg_${_key}}")
    endif()
  endforeach()
  add_test(NAME cli.${name} COMMAND ${CMAKE_COMMAND} -DCMD=${_cmd} -DWORK=${_cliWork}/${name} ${_defs}
           -P ${CMAKE_CURRENT_SOURCE_DIR}/cli_expect.cmake)
endfunction()

# A header file gives its own layout: --raw-endian is refused like --raw-dims (its default is no
# byte order given), and any --raw-* option with a data set, which has no raw file to describe.
set(_headerRefused "header.nhdr: a raw layout \\(dimensions, type, byte order, spacing or skip")
kdswap_cli_case(RenderRawEndianOnAHeaderFileIsRefused EXPECT "${_headerRefused}"
                ARGS render --volume header.nhdr --raw-endian big --size 16x16 --out o.png)
kdswap_cli_case(InfoRawEndianOnAHeaderFileIsRefused EXPECT "${_headerRefused}"
                ARGS info --raw-endian big header.nhdr)
# A data set's size with a stray 'x' is refused, not read as the size before it.
kdswap_cli_case(RenderDatasetSizeWithATrailingXIsRefused
                EXPECT "kdswap: data set .phantom:16x.: size .16x. is not N or WxHxD"
                ARGS render --dataset phantom:16x --size 16x16 --out o.png)
kdswap_cli_case(RenderRawDimsWithADatasetAreRefused
                EXPECT "--raw-dims describes a raw --volume file. it does not apply to --dataset phantom:16"
                ARGS render ${_tiny} --raw-dims 66x66x66)
kdswap_cli_case(InfoRawTypeWithADatasetIsRefused
                EXPECT "--raw-type describes a raw --volume file. it does not apply to --dataset phantom:16"
                ARGS info --dataset phantom:16 --raw-type uint8)
kdswap_cli_case(BenchRawSkipWithADatasetIsRefused
                EXPECT "--raw-skip describes a raw --volume file. it does not apply to --dataset phantom:16"
                ARGS bench ${_benchTiny} --raw-skip 8 --out-dir b)
kdswap_cli_case(ExportRawDimsWithADatasetAreRefused
                EXPECT "--raw-dims describes a raw --volume file. it does not apply to --dataset phantom:16"
                ARGS export --dataset phantom:16 --raw-dims 4x4x4 --out x.nrrd)
kdswap_cli_case(BenchRawDimsWithTargetsAreRefused
                EXPECT "--raw-dims describes a raw --volume file. it does not apply to --targets"
                ARGS bench --targets --raw-dims 4x4x4)
# The fixed modes run their own cells: a grid option there would be silently ignored.
kdswap_cli_case(BenchDatasetWithTargetsIsRefused
                EXPECT "kdswap: --dataset sets up a grid run. --targets runs its own fixed cells"
                ARGS bench --targets --dataset vessels:64)
kdswap_cli_case(BenchSizesWithPaperIsRefused
                EXPECT "kdswap: --sizes sets up a grid run. --paper runs its own fixed cells"
                ARGS bench --paper --sizes 64)
kdswap_cli_case(BenchOutDirWithMicroIsRefused
                EXPECT "kdswap: --out-dir sets up a grid run. --micro runs its own fixed cells"
                ARGS bench --micro --out-dir b)
kdswap_cli_case(BenchWavesWithTargetsIsRefused
                EXPECT "kdswap: --waves goes with a grid run or --paper. --targets measures each scene with and without waves itself"
                ARGS bench --targets --waves)
kdswap_cli_case(BenchWavesWithMicroIsRefused
                EXPECT "kdswap: --waves goes with a grid run or --paper. --micro times kernels alone"
                ARGS bench --micro --waves)
kdswap_cli_case(BenchFramesWithMicroIsRefused EXPECT "kdswap: --frames does not apply to --micro"
                ARGS bench --micro --frames 3)
kdswap_cli_case(BenchHeadWithoutTargetsIsRefused EXPECT "kdswap: --head goes with --targets"
                ARGS bench ${_benchTiny} --head /nonexistent/head.nhdr --out-dir b)

# A raw file without a layout: the message says what is missing and how to give it with the
# command at hand (every command that reads a --volume has the --raw-* options).
set(_bothOptions "plain.raw: raw file layout unknown: give --raw-dims WxHxD and --raw-type TYPE, or name it NAME_WxHxD_TYPE.raw")
kdswap_cli_case(BenchRawFileWithoutLayoutNamesBothOptions EXPECT "${_bothOptions}"
                ARGS bench --volume plain.raw --sizes 16 --nodes 1 --frames 1 --out-dir b)
kdswap_cli_case(ExportRawFileWithoutLayoutNamesBothOptions EXPECT "${_bothOptions}" ARGS export --volume plain.raw --out x.nrrd)
kdswap_cli_case(ExportRawTypeWithoutRawDimsSaysTheDimensionsAreMissing
                EXPECT "plain.raw: raw file layout unknown: --raw-dims WxHxD is missing"
                ARGS export --volume plain.raw --raw-type uint8 --out x.nrrd)
kdswap_cli_case(RenderRawDimsWithoutRawTypeSaysTheTypeIsMissing
                EXPECT "plain.raw: raw file layout unknown: --raw-type TYPE is missing .TYPE: int8 uint8 "
                ARGS render --volume plain.raw --raw-dims 66x66x66 --size 16x16 --out o.png)
kdswap_cli_case(RenderRawTypeWithoutRawDimsSaysTheDimensionsAreMissing
                EXPECT "plain.raw: raw file layout unknown: --raw-dims WxHxD is missing"
                ARGS render --volume plain.raw --raw-type uint8 --size 16x16 --out o.png)
kdswap_cli_case(InfoRawFileWithoutLayoutNamesBothOptions EXPECT "${_bothOptions}" ARGS info plain.raw)

# Failures that used to print a library's text.
kdswap_cli_case(BenchOutDirThatCannotBeMadeIsOneLineNamingTheOption
                EXPECT "kdswap: --out-dir /proc/kdswap-no-such-folder: cannot create the folder \\("
                FORBID "unexpected error|filesystem error"
                ARGS bench ${_benchTiny} --out-dir /proc/kdswap-no-such-folder)
kdswap_cli_case(TransferFunctionThatIsNotJsonNamesTheFileAndPosition
                EXPECT "bad.json: not valid JSON: parse error at line 2, column 13: syntax error while parsing value - invalid literal. last read: '[^']*\\\\xC3'"
                FORBID "json.exception" ARGS render ${_tiny} --tf bad.json)

# Values out of range are refused, not clamped or wrapped.
kdswap_cli_case(InjectedDelayAboveAnHourIsRefused
                EXPECT "--inject-fault .delay:1:0:1e300.: DELAY_S must be from 0 to 3600 seconds"
                ARGS render ${_tiny} --nodes 4 --inject-fault delay:1:0:1e300)
kdswap_cli_case(RawSkipBeyond64BitsIsRefused EXPECT "--raw-skip: .99999999999999999999. is out of range"
                ARGS info --raw-skip 99999999999999999999 --raw-dims 2x2x2 --raw-type uint8 plain.raw)
kdswap_cli_case(BenchNegativeRawSkipIsRefused EXPECT "kdswap: --raw-skip -1: expected a number of bytes >= 0"
                ARGS bench --volume plain.raw --raw-skip -1 --raw-dims 2x2x2 --raw-type uint8 --sizes 16 --nodes 1 --frames 1 --out-dir b)

# Every error names its option; a node is named once.
kdswap_cli_case(UnknownCompositeNamesTheOption
                EXPECT "kdswap: --composite .foo.: expected one of binary-swap, binary-tree, sequential, direct-send, radix-k, 2-3-swap, telescoping"
                ARGS render ${_tiny} --composite foo)
kdswap_cli_case(BenchUnknownCompositeNamesTheOption EXPECT "kdswap: --composite .foo.: expected one of binary-swap"
                ARGS bench ${_benchTiny} --composite binary-swap,foo --out-dir b)
kdswap_cli_case(RenderPassesOutsideItsRangeAreRefused EXPECT "kdswap: --passes: Value 0 not in range 1 to 256"
                ARGS render ${_tiny} --passes 0)
kdswap_cli_case(UnknownPartitionNamesTheOption EXPECT "kdswap: --partition .oct.: expected kd or slab"
                ARGS render ${_tiny} --partition oct)
kdswap_cli_case(UnknownProjectionNamesTheOption EXPECT "kdswap: --projection .fisheye.: expected perspective or orthographic"
                ARGS render ${_tiny} --projection fisheye)
kdswap_cli_case(UnknownUpAxisNamesTheOption EXPECT "kdswap: --up .\\+w.: expected one of \\+x -x \\+y -y \\+z -z"
                ARGS render ${_tiny} --up +w)
kdswap_cli_case(CorruptedMessageNamesTheReceivingNodeOnce
                EXPECT "kdswap: node [0-9]+: message from node 1 \\(tag [0-9]+\\) failed its checksum"
                FORBID "node [0-9]+: node [0-9]+:" ARGS render ${_tiny} --nodes 4 --inject-fault corrupt:1)
kdswap_cli_case(StepThatIsNotANumberNamesTheOption EXPECT "kdswap: --step: .abc. is not a number"
                FORBID "Could not convert" ARGS render ${_tiny} --step abc)
kdswap_cli_case(NodesThatIsNotAWholeNumberNamesTheOption EXPECT "kdswap: --nodes: .2.5. is not a whole number"
                ARGS render ${_tiny} --nodes 2.5)
kdswap_cli_case(BenchFramesThatIsNotAWholeNumberNamesTheOption EXPECT "kdswap: --frames: .x. is not a whole number"
                ARGS bench --dataset phantom:16 --sizes 16 --nodes 1 --frames x --out-dir b)

# Output for people: grammar, and a log without one line per frame.
kdswap_cli_case(RenderSummaryOfOneNodeSaysNode CODE 0 STDOUT "^1 node, 16x16, binary-swap" ARGS render ${_tiny})
kdswap_cli_case(BenchProgressInALogHasALineWhenACellStartsAndEnds CODE 0
                EXPECT "^\\[0/2 cells\\] [^[]*\\[1/2 cells\\] [^[]*\\[1/2 cells\\] [^[]*\\[2/2 cells\\] [^[]*$"
                ARGS bench --dataset phantom:16 --sizes 16 --nodes 1,2 --frames 3 --out-dir b)
# Interleaved, the cell changes every frame: a log gets the first line and one per cell ended.
kdswap_cli_case(BenchInterleavedProgressInALogHasALinePerCellEnded CODE 0
                EXPECT "^\\[0/2 cells\\] [^[]*\\[1/2 cells\\] [^[]*\\[2/2 cells\\] [^[]*$"
                ARGS bench --dataset phantom:16 --sizes 16 --nodes 1,2 --frames 3 --interleave --out-dir b)

# A volume file given to --dataset (kdswap-gui takes files there) names the way to open it; a name
# that is no file and no data set keeps the list of data sets.
kdswap_cli_case(RenderFileInDatasetNamesVolume
                EXPECT "^kdswap: --dataset .data/head\\.nhdr.: not a built-in data set \\(phantom, turbulence, vessels\\); a volume file is opened with --volume data/head\\.nhdr\n$"
                ARGS render --dataset data/head.nhdr --size 16x16 --out o.png)
kdswap_cli_case(BenchFileInDatasetNamesVolume EXPECT "a volume file is opened with --volume scan\\.raw"
                ARGS bench --dataset scan.raw --sizes 16 --nodes 1 --frames 1)
kdswap_cli_case(ExportFileInDatasetNamesVolume EXPECT "a volume file is opened with --volume scan\\.raw"
                ARGS export --dataset scan.raw --out o.nrrd)
kdswap_cli_case(InfoFileInDatasetNamesVolume EXPECT "a volume file is opened with --volume scan\\.raw"
                ARGS info --dataset scan.raw)
kdswap_cli_case(RenderUnknownDatasetListsTheDataSets
                EXPECT "data set .foo.: unknown \\(built-in data sets: phantom, turbulence, vessels\\)"
                ARGS render --dataset foo --size 16x16 --out o.png)

# The GUI's help is complete without the sources: every strategy, the node range, the script format.
if(TARGET kdswap-gui)
  kdswap_cli_case(GuiHelpListsStrategiesNodeRangeAndScriptCommands PROGRAM kdswap-gui CODE 0
                  STDOUT "P, 1\\.\\.4096.*binary-swap, binary-tree, sequential, direct-send, radix-k, 2-3-swap, telescoping.*move TARGET. glide DX DY FRAMES"
                  FORBID "input_script\\.h|binary-swap, \\.\\.\\." ARGS --help)
  # --volume as in kdswap render; with --dataset as well, which one to open is not guessed.
  kdswap_cli_case(GuiVolumeAndDatasetTogetherAreRefused PROGRAM kdswap-gui
                  EXPECT "kdswap-gui: --dataset excludes --volume" ARGS --volume scan.raw --dataset phantom:16)
  # Checked before any window opens, so it needs no display.
  kdswap_cli_case(GuiUnknownUpAxisIsRefused PROGRAM kdswap-gui
                  EXPECT "kdswap-gui: --up .q.: expected one of \\+x -x \\+y -y \\+z -z" ARGS --up q)
  kdswap_cli_case(GuiRefinePassesOutsideTheirRangeAreRefused PROGRAM kdswap-gui
                  EXPECT "kdswap-gui: --refine 0: expected 1\\.\\.64" ARGS --refine 0)
  # Numbers are read as kdswap reads them, not with the argument parser's own words.
  kdswap_cli_case(GuiNodesThatAreNotAWholeNumberAreRefused PROGRAM kdswap-gui
                  EXPECT "kdswap-gui: --nodes: .1\\.5. is not a whole number" ARGS --nodes 1.5)
  kdswap_cli_case(GuiUiScaleOutsideItsRangeIsRefused PROGRAM kdswap-gui
                  EXPECT "kdswap-gui: --ui-scale 5: expected 0\\.5\\.\\.4" ARGS --ui-scale 5)
  kdswap_cli_case(GuiWindowSizeWithAThirdSideIsRefused PROGRAM kdswap-gui
                  EXPECT "kdswap-gui: --size .1600x1000x5.: expected WxH" ARGS --size 1600x1000x5)
endif()

# Front-to-back waves render each node's one brick in visibility order: over-decomposition (bricks
# handed out on demand) is refused with them rather than silently rendered without waves.
kdswap_cli_case(RenderWavesWithOverDecompositionAreRefused
                EXPECT "--waves renders each node.s one brick in visibility order: give --bricks-per-node 1"
                ARGS render ${_tiny} --nodes 4 --waves --bricks-per-node 4)
kdswap_cli_case(BenchWavesWithOverDecompositionAreRefused
                EXPECT "--waves renders each node.s one brick in visibility order: give --bricks-per-node 1"
                ARGS bench ${_benchTiny} --waves --bricks-per-node 1,4)
