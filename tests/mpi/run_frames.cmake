# Several frames over MPI (cmake -P): kdswap-mpi --frames 3 --orbit 20 keeps the bricks loaded and
# turns the view; its image (the last frame, at azimuth 30 + 2 x 20) must equal kdswap render's at
# that view bit for bit, and the stats must hold the three measured frames and their medians.
# In: KDSWAP, KDSWAP_MPI, COMPARE, MPIEXEC, MPIFLAGS (;-list), WORK.
file(MAKE_DIRECTORY ${WORK})
set(scene --dataset phantom:48 --size 96x80)
set(mpi ${MPIEXEC} ${MPIFLAGS} -np 2 ${KDSWAP_MPI} render ${scene} --view 30,15 --nodes-per-rank 2 --frames 3
    --orbit 20 --verify --out ${WORK}/mpi.exr --stats ${WORK}/mpi.json)
set(inproc ${KDSWAP} render ${scene} --view 70,15 --nodes 4 --quiet --out ${WORK}/inproc.exr)
foreach(step mpi inproc)
  string(REPLACE ";" " " shown "${${step}}")
  message(STATUS "${shown}")
  execute_process(COMMAND ${${step}} RESULT_VARIABLE rc OUTPUT_VARIABLE out TIMEOUT 60)
  message(STATUS "${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}); reproduce with:\n  ${shown}")
  endif()
endforeach()
execute_process(COMMAND ${COMPARE} ${WORK}/mpi.exr ${WORK}/inproc.exr 0 RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the last MPI frame differs from kdswap render at --view 70,15")
endif()
file(READ ${WORK}/mpi.json stats)
string(JSON count GET "${stats}" frames count)
string(JSON walls LENGTH "${stats}" frames wall_s)
string(JSON medianWall GET "${stats}" frames median wall_s)
if(NOT count EQUAL 3 OR NOT walls EQUAL 3 OR NOT medianWall GREATER 0)
  message(FATAL_ERROR "stats frames: count ${count}, ${walls} wall times, median ${medianWall}")
endif()
