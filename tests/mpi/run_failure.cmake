# A rank that cannot open its volume (cmake -P): the run must end, non-zero, with rank 0 naming
# that rank, instead of hanging. MPMD launch: ranks 0..R-2 get the data set, the last rank a
# volume file that does not exist (as on a host without the shared file system).
# In: KDSWAP_MPI, MPIEXEC, MPIFLAGS (;-list), RANKS, SCENE (;-list), WORK.
math(EXPR good "${RANKS} - 1")
math(EXPR bad "${RANKS} - 1")
file(MAKE_DIRECTORY ${WORK})
set(cmd ${MPIEXEC} ${MPIFLAGS} -np ${good} ${KDSWAP_MPI} render ${SCENE} --out ${WORK}/never.png
    : -np 1 ${KDSWAP_MPI} render --volume ${WORK}/missing.nrrd --size 96x80 --out ${WORK}/never.png)
string(REPLACE ";" " " shown "${cmd}")
message(STATUS "${shown}")
execute_process(COMMAND ${cmd} RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out TIMEOUT 60)
message(STATUS "exit ${rc}; stderr:\n${err}")
if(rc EQUAL 0 OR rc MATCHES "timeout")
  message(FATAL_ERROR "expected a failing exit, got '${rc}'; reproduce with:\n  ${shown}")
endif()
if(NOT err MATCHES "kdswap-mpi: rank ${bad}: .*missing.nrrd")
  message(FATAL_ERROR "rank 0 did not name rank ${bad} and the file; reproduce with:\n  ${shown}")
endif()
if(EXISTS ${WORK}/never.png)
  message(FATAL_ERROR "a failed run wrote ${WORK}/never.png")
endif()
