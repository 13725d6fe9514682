# metrosync-mpi (docs/cluster.md, tools/cli/sweep_mpi.h): `metrosync sweep` over MPI processes
# (`metrosync sweep` started as one of several ranks execs it: tools/cli/mpi_forward.h).
# MPI is optional (Debian: libopenmpi-dev openmpi-bin) and linked into this executable only:
#   metrosync_sweep_mpi  tools/cli/sweep_mpi.cpp  (the one file of the folder that sees MPI)
#   metrosync-mpi        tools/metrosync_mpi.cpp
# so that `metrosync`, the Python module and the other tests never load libmpi. The file leaves
# the tools/cli library's sources here; tests/mpi is built only with MPI (CMakeLists.txt skips
# the folder otherwise). Included once the folder libraries and `metrosync` exist.
find_package(MPI COMPONENTS CXX)

get_target_property(_cli_srcs metrosync_tools_cli SOURCES)
list(REMOVE_ITEM _cli_srcs ${CMAKE_SOURCE_DIR}/tools/cli/sweep_mpi.cpp)
set_target_properties(metrosync_tools_cli PROPERTIES SOURCES "${_cli_srcs}")

set(METROSYNC_HAVE_MPI ${MPI_CXX_FOUND})
if(MPI_CXX_FOUND)
  add_library(metrosync_sweep_mpi STATIC ${CMAKE_SOURCE_DIR}/tools/cli/sweep_mpi.cpp)
  target_include_directories(metrosync_sweep_mpi PUBLIC ${CMAKE_SOURCE_DIR})
  target_link_libraries(metrosync_sweep_mpi PUBLIC metrosync_tools_cli MPI::MPI_CXX)
  metrosync_simbody_target(metrosync_sweep_mpi)
  # metrosync-mpi-faults: the same with the tests' fault hooks (tools/cli/fault_hooks.h)
  foreach(prog metrosync-mpi metrosync-mpi-faults)
    add_executable(${prog} tools/metrosync_mpi.cpp)
    target_link_libraries(${prog} PRIVATE metrosync_sweep_mpi)
    metrosync_link_heavy(${prog})
  endforeach()
  target_sources(metrosync-mpi-faults PRIVATE ${CMAKE_SOURCE_DIR}/tests/faults/install_faults.cpp)
  message(STATUS "metrosync-mpi: MPI ${MPI_CXX_VERSION} (${MPIEXEC_EXECUTABLE})")
else()
  message(STATUS "metrosync-mpi: not built (needs MPI: apt-get install libopenmpi-dev openmpi-bin)")
endif()
