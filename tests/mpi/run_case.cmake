# One MPI image test (cmake -P): the in-process render with P nodes, then mpirun of kdswap-mpi with
# R ranks x K nodes; their images must agree to 1e-5 (early ray termination off), and kdswap-mpi
# --verify checks against the single-node reference.
# In: KDSWAP, KDSWAP_MPI, COMPARE, MPIEXEC, MPIFLAGS (;-list), RANKS, PER_RANK, WORK, SCENE (;-list).
math(EXPR nodes "${RANKS} * ${PER_RANK}")
file(MAKE_DIRECTORY ${WORK})
set(inproc ${KDSWAP} render ${SCENE} --ert 1 --nodes ${nodes} --quiet --out ${WORK}/inproc.exr)
set(mpi ${MPIEXEC} ${MPIFLAGS} -np ${RANKS} ${KDSWAP_MPI} render ${SCENE} --ert 1 --nodes-per-rank ${PER_RANK}
    --verify --out ${WORK}/mpi.exr --stats ${WORK}/mpi.json)
foreach(step inproc mpi)
  string(REPLACE ";" " " shown "${${step}}")
  message(STATUS "${shown}")
  execute_process(COMMAND ${${step}} RESULT_VARIABLE rc TIMEOUT 60)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}); reproduce with:\n  ${shown}")
  endif()
endforeach()
execute_process(COMMAND ${COMPARE} ${WORK}/mpi.exr ${WORK}/inproc.exr 1e-5 RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  string(REPLACE ";" " " shown "${mpi}")
  message(FATAL_ERROR "MPI image differs from the in-process one (diff image beside mpi.exr); reproduce with:\n  ${shown}")
endif()
file(READ ${WORK}/mpi.json stats)
string(JSON n GET "${stats}" nodes)
string(JSON ranks GET "${stats}" ranks)
string(JSON perNode LENGTH "${stats}" per_node)
if(NOT n EQUAL nodes OR NOT ranks EQUAL RANKS OR NOT perNode EQUAL nodes)
  message(FATAL_ERROR "stats: nodes ${n}, ranks ${ranks}, per_node ${perNode}; expected ${nodes}, ${RANKS}, ${nodes}")
endif()
