# Runs one command line (cmake -P, from cli_option_errors.cmake) and checks what a user sees:
# CMD (a list), CODE the exit code (default 2). A refusal (CODE 2) must be one printable ASCII line
# on stderr matching EXPECT; otherwise EXPECT is matched against stderr and STDOUT against stdout.
# FORBID must match neither. WORK holds the inputs this makes: plain.raw (no layout in its name),
# header.nhdr (a header file, refused before it is read) and bad.json (a byte that is not ASCII
# where a value should start).
if(NOT DEFINED CODE)
  set(CODE 2)
endif()
file(MAKE_DIRECTORY "${WORK}")
file(WRITE "${WORK}/plain.raw" "12345678")
file(WRITE "${WORK}/header.nhdr" "NRRD0004\n")
string(ASCII 195 _notAscii)
file(WRITE "${WORK}/bad.json" "{\n  \"points\": ${_notAscii}\n}\n")

execute_process(COMMAND ${CMD} WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE _code OUTPUT_VARIABLE _out
                ERROR_VARIABLE _err TIMEOUT 120)
string(REPLACE ";" " " _shown "${CMD}")
set(_report "command: ${_shown}\nexit code: ${_code}\nstderr:\n${_err}\nstdout (end):\n")
string(LENGTH "${_out}" _len)
if(_len GREATER 2000)
  math(EXPR _from "${_len} - 2000")
  string(SUBSTRING "${_out}" ${_from} -1 _tail)
else()
  set(_tail "${_out}")
endif()
string(APPEND _report "${_tail}")

if(NOT "${_code}" STREQUAL "${CODE}")
  message(FATAL_ERROR "expected exit code ${CODE}\n${_report}")
endif()
if(DEFINED EXPECT AND NOT _err MATCHES "${EXPECT}")
  message(FATAL_ERROR "stderr does not match: ${EXPECT}\n${_report}")
endif()
if(DEFINED STDOUT AND NOT _out MATCHES "${STDOUT}")
  message(FATAL_ERROR "stdout does not match: ${STDOUT}\n${_report}")
endif()
if(DEFINED FORBID AND "${_out}${_err}" MATCHES "${FORBID}")
  message(FATAL_ERROR "the output matches what it must not: ${FORBID}\n${_report}")
endif()
if(CODE EQUAL 2)
  if(NOT _err MATCHES "^[^\n]+\n$")
    message(FATAL_ERROR "a refusal must be one line on stderr\n${_report}")
  endif()
  string(REGEX MATCH "[^ -~\n]" _bad "${_err}")
  if(NOT _bad STREQUAL "")
    message(FATAL_ERROR "stderr holds a byte that is not printable ASCII\n${_report}")
  endif()
endif()
