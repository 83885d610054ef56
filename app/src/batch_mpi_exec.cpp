// `surfcert batch --mpi` in the `surfcert` executable of a build with MPI (batch_mpi.hpp):
// MPI runs in the `surfcert-mpi` executable next to it, which app/cli execs with the same
// arguments, so that `surfcert` itself does not load libmpi and its chain (Open RTE/PAL, hwloc,
// libevent, udev, zlib: ~85 page faults, 5-8 ms of every process's startup). The compute
// child (`batch --mpi-child`, batch_child.cpp) needs no MPI and runs here.
#include "surfcert/app/batch_mpi.hpp"

#include <stdexcept>

namespace surfcert::app {

bool mpi_available() {
  return true;
}

const char* mpi_executable() {
  return "surfcert-mpi";
}

BatchStats run_batch_mpi(int, const MpiBatchOptions&, bool*, MpiBatchReport*) {
  throw std::logic_error("batch --mpi runs in surfcert-mpi (app/cli execs it)");
}

} // namespace surfcert::app
