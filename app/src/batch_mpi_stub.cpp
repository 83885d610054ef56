// `surfcert batch --mpi` in a build without MPI (CMake did not find it): batch_mpi.hpp's
// functions say so.
#include "surfcert/app/batch_mpi.hpp"

#include <stdexcept>

namespace surfcert::app {

bool mpi_available() {
  return false;
}

const char* mpi_executable() {
  return nullptr;
}

BatchStats run_batch_mpi(int, const MpiBatchOptions&, bool*, MpiBatchReport*) {
  throw std::runtime_error("this surfcert was built without MPI");
}

BatchStats run_batch_child(int, int, const MpiBatchOptions&) {
  throw std::runtime_error("this surfcert was built without MPI");
}

} // namespace surfcert::app
