# An MPMD launch whose last rank was started with another command line than the others (cmake -P):
# the run must end quickly, non-zero, with one line naming that rank and what differs, and write
# no image. In: KDSWAP_MPI, MPIEXEC, MPIFLAGS (;-list), RANKS, SCENE (;-list, ranks 0..R-2),
# OTHER (;-list, the last rank), EXPECT (regex on stderr), WORK.
math(EXPR good "${RANKS} - 1")
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(cmd ${MPIEXEC} ${MPIFLAGS} -np ${good} ${KDSWAP_MPI} render ${SCENE} --out ${WORK}/never.png
    : -np 1 ${KDSWAP_MPI} render ${OTHER} --out ${WORK}/never.png)
string(REPLACE ";" " " shown "${cmd}")
message(STATUS "${shown}")
execute_process(COMMAND ${cmd} RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out TIMEOUT 60)
message(STATUS "exit ${rc}; stderr:\n${err}")
if(rc EQUAL 0 OR rc MATCHES "timeout")
  message(FATAL_ERROR "expected a failing exit, got '${rc}'; reproduce with:\n  ${shown}")
endif()
if(NOT err MATCHES "${EXPECT}")
  message(FATAL_ERROR "stderr does not match '${EXPECT}'; reproduce with:\n  ${shown}")
endif()
if(EXISTS ${WORK}/never.png)
  message(FATAL_ERROR "a refused run wrote ${WORK}/never.png")
endif()
