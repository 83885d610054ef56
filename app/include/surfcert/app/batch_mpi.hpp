// surfcert::app `surfcert batch --mpi`: the batch spread over the ranks of an MPI job (Open
// MPI's mpirun, Slurm's srun), with on-demand scheduling, a resumable checkpoint, a second pass
// for lines undecided by their budget, and worker processes whose death costs only their lines.
//
// What it represents and its contract:
//   - rank 0 reads JSON lines from stdin and writes one answer line per input line to out_fd,
//     in input order (ordered) or as completed; every answer is byte for byte the one the
//     single-process batch writes for that line (answer_batch_line, batch_line.hpp), apart
//     from its own "time_ms"; the BatchStats are the single-process batch's.
//   - the other ranks are workers. Each runs its lines in a compute child process: this same
//     executable run as `surfcert batch --mpi-child` (the single-process batch pipeline, its
//     `threads` threads, framed lines: run_batch_child). A worker asks rank 0 for work when its
//     child has room, for groups of 1 to 16 lines sized from the lines' measured times (fast
//     lines share a message; a slow line holds no queue behind it), so a slow line never
//     stalls the other workers: a worker whose every thread is on a slow line gives back the
//     lines waiting behind them. With one rank, rank 0 drives a compute child itself.
//   - a compute child that dies (killed, out of memory) loses only the lines it held: each is
//     retried once on another worker (if any), and a line lost twice is answered with an
//     "internal" error line; the run completes.
//   - the death of a worker rank itself (killed, its node lost) costs only its lines when the
//     job runs with Open MPI's recovery (`mpirun --enable-recovery`, which keeps the other
//     processes alive; rank 0 sees it as OMPI_MCA_orte_enable_recovery in its environment).
//     Then every rank sends a heartbeat to rank 0 (and rank 0 to each worker) at least every
//     min(1 s, rank_timeout_s / 5); a worker silent for rank_timeout_s (or whose send failed)
//     is dead: its lines follow the rule of a dead compute child, it is never sent to again,
//     and once no worker is left rank 0 answers the remaining lines through a compute child of
//     its own. A worker that hears nothing from rank 0 for rank_timeout_s leaves. The run ends
//     with a handshake (stop, goodbye) and without MPI_Finalize on every rank, since Open MPI
//     4.1's MPI_Finalize waits for the dead ranks forever; mpirun then exits with status 0
//     whatever rank 0 returns (Open MPI 4.1.4 under --enable-recovery), so the batch's status
//     is in rank 0's summary on stderr (`exit=N`, app/cli). Without recovery the death of
//     any rank ends the job (mpirun kills the others); a restart with the same checkpoint
//     resumes it. Open MPI 4.1 has no MPI-level fault tolerance (ULFM) to do better.
//   - checkpoint (not empty): every answer is appended to that file as it arrives (one record
//     per line: line number, a hash of the input line, the answer), fsync'd at least every
//     0.2 s and at the end; a run restarted on the same input skips every line answered there
//     and writes the same final output. A record whose line hash differs from the input is an
//     InputError (another input), a torn last record (a killed run) is dropped.
//   - retry_budget_ms > 0: lines answered undecided with reason "budget" are run again, after
//     every first-pass line, with "budget_ms" set to retry_budget_ms; their answer is the
//     second pass's.
// These functions are defined by the optional component the executables link
// (app/CMakeLists.txt). When CMake finds MPI, the build makes two executables from the same
// main (app/cli): `surfcert-mpi`, linked with MPI (surfcert_batch_mpi), and `surfcert`, linked
// without it (surfcert_batch_mpi_exec: libmpi and its chain cost every process ~85 page
// faults, 5-8 ms at startup), whose `batch --mpi` replaces its own image with the
// `surfcert-mpi` next to it (execv, same pid, same arguments and environment, so MPI_Init runs
// in that image under mpirun as it would have in this one): mpi_executable() names it there,
// and run_batch_mpi is never called. Without MPI, stubs: mpi_available() false,
// mpi_executable() null, the others throw std::runtime_error.
#pragma once

#include "surfcert/app/scene.hpp"
#include "surfcert/certify/detail.hpp"

#include <string>
#include <vector>

namespace surfcert::app {

struct MpiBatchOptions {
  certify::Mode mode = certify::Mode::Filtered;
  certify::Detail detail = certify::Detail::Full;
  double budget_ms = 0; ///< default per-line budget (a line's "budget_ms" overrides)
  int threads = 1;      ///< threads of each compute child
  bool ordered = true;
  std::string checkpoint;     ///< empty: none
  double retry_budget_ms = 0; ///< 0: no second pass
  /// With Open MPI's recovery: a rank silent this long is dead (see above).
  double rank_timeout_s = 30;
  /// The compute child's command line: the surfcert executable, "batch", "--mpi-child" and
  /// the options above (mode, detail, budget, threads) as the CLI spells them.
  std::vector<std::string> child_command;
};

/// What the run did beyond the statistics (rank 0).
struct MpiBatchReport {
  long resumed = 0;      ///< lines answered from the checkpoint
  long retried = 0;      ///< lines lost by a compute child or worker rank that died, sent again
  long lost_twice = 0;   ///< lines lost twice, answered with an "internal" error line
  long second_pass = 0;  ///< lines undecided by their budget, run again (--retry-undecided)
  long returned = 0;     ///< lines a worker gave back unstarted (its threads on slow lines)
  long dead_ranks = 0;   ///< worker ranks found dead (only with Open MPI's recovery)
  bool recovery = false; ///< the job ran with Open MPI's recovery (heartbeats, no MPI_Finalize)
  /// Rank 0 answered lines through a compute child of its own because no worker was left
  /// (only with Open MPI's recovery; not the one-rank job, where it always does).
  bool local_fallback = false;
};

/// Whether this build has MPI (CMake found it): `batch --mpi` runs, here or in mpi_executable().
bool mpi_available();

/// The file name of the executable, in this executable's directory, that runs `batch --mpi`
/// in place of this one (execv with the same arguments): "surfcert-mpi" in the `surfcert`
/// of a build with MPI; null where run_batch_mpi runs here (surfcert-mpi) or nowhere (no MPI).
const char* mpi_executable();

/// Initializes MPI, runs rank 0 or a worker (see above), finalizes MPI. On rank 0 the stats of
/// the run; on workers all zero with *is_root = false (they write nothing).
BatchStats run_batch_mpi(int out_fd, const MpiBatchOptions& options, bool* is_root,
                         MpiBatchReport* report);

/// The compute child (`surfcert batch --mpi-child`): framed lines "<line_no>\t<json>" on in_fd,
/// framed answers "<line_no> <status> <kind|-> <fallback 0|1> <microseconds>\t<answer>" on
/// out_fd, as completed, through the single-process batch pipeline.
BatchStats run_batch_child(int in_fd, int out_fd, const MpiBatchOptions& options);

} // namespace surfcert::app
