// Running on several machines: the processes of one MPI job (Open MPI,
// `mpirun -np N radiant …`) and the few collective operations Radiant needs.
//
// Every rank runs the same command on the same inputs and does the same
// deterministic work, except where a stage splits it: the render driver
// gives each rank its share of the image's tiles (render/driver.h), the
// stochastic solver each rank its share of every iteration's rays
// (radiosity/stochastic_jacobi.cpp). Their results are summed across ranks
// with the functions below, and rank 0 writes the outputs. Built without MPI,
// or run without mpirun, there is one rank and every function is a no-op,
// so single-process runs neither need nor pay for an MPI library.
//
// Only the main thread calls these (MPI_THREAD_FUNNELED): the threads inside
// a rank (oneTBB) never communicate.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace radiant::cluster {

/// Joins the MPI job when the process was started by an MPI launcher
/// (mpirun, mpiexec, srun: they set OMPI_COMM_WORLD_SIZE, PMIX_RANK or
/// PMI_RANK), and leaves it when destroyed. One per process, in main().
class Session {
 public:
  Session(int &argc, char **&argv);
  ~Session();
  Session(const Session &) = delete;
  Session &operator=(const Session &) = delete;
};

/// This process's rank, 0 … size() − 1; 0 without MPI.
int rank();
/// The number of ranks; 1 without MPI, and 1 on rank 0 inside a RootAlone.
int size();
/// More than one rank: work is split and summed.
inline bool distributed() {
  return size() > 1;
}
/// Rank 0: the one that prints progress and writes files.
inline bool isRoot() {
  return rank() == 0;
}
/// Whether this radiant was built with MPI (radiant --version says).
bool builtWithMpi();

/// Element-wise sums over all ranks, the result on every rank (MPI_Allreduce).
void sumOnAllRanks(double *values, size_t count);
void sumOnAllRanks(int64_t *values, size_t count);
void sumOnAllRanks(uint32_t *values, size_t count);
void sumOnAllRanks(uint8_t *values, size_t count);
/// Element-wise sums over all ranks, the result on rank 0 only (MPI_Reduce;
/// other ranks' arrays are left as they were).
void sumOnRoot(double *values, size_t count);
void sumOnRoot(uint32_t *values, size_t count);
void sumOnRoot(uint8_t *values, size_t count);
/// Every rank's `mine`, on every rank, in rank order (MPI_Allgatherv):
/// rank r's bytes are all[starts[r] .. starts[r + 1]).
std::vector<uint8_t> gatherFromAllRanks(const std::vector<uint8_t> &mine, std::vector<size_t> &starts);

/// Entries `which` of `values`, each computed by one rank (the one for
/// which `owns(i)` is true) and not yet known to the others, on every rank
/// afterwards, bit for bit: each rank sends its own entries, each with its
/// position in `which`, and copies in everyone else's. (A byte-wise sum of
/// every rank's entries and zeros did the same, but moved and added every
/// entry's bytes on every rank: twice the traffic, and a reduction besides.)
/// For a trivially copyable T (an estimate, a Bands).
template <typename T, typename Owns>
void shareOwnedEntries(std::vector<T> &values, const std::vector<size_t> &which, const Owns &owns) {
  static_assert(std::is_trivially_copyable_v<T>, "entries travel as their bytes");
  if (!distributed() || which.empty()) return;
  constexpr size_t kRecord = sizeof(uint64_t) + sizeof(T);  // position in `which`, then the value
  std::vector<uint8_t> mine;
  for (size_t k = 0; k < which.size(); ++k)
    if (owns(which[k])) {
      const size_t at = mine.size();
      mine.resize(at + kRecord);
      const uint64_t position = k;
      std::memcpy(&mine[at], &position, sizeof position);
      std::memcpy(&mine[at + sizeof position], &values[which[k]], sizeof(T));
    }
  std::vector<size_t> starts;
  const std::vector<uint8_t> all = gatherFromAllRanks(mine, starts);
  for (int r = 0; r < size(); ++r) {
    if (r == rank()) continue;
    for (size_t at = starts[size_t(r)]; at + kRecord <= starts[size_t(r) + 1]; at += kRecord) {
      uint64_t position = 0;
      std::memcpy(&position, &all[at], sizeof position);
      std::memcpy(&values[which[position]], &all[at + sizeof position], sizeof(T));
    }
  }
}

/// Rank 0's value, on every rank (MPI_Bcast).
int64_t fromRoot(int64_t value);
double fromRoot(double value);
/// True on every rank when it is true on any (an interrupt on one node).
bool anyRank(bool value);

/// Rank 0 works as one process while this lives: size() is 1 and every
/// collective above is a no-op, so that it runs a stage alone (a solve too
/// small to be worth sharing: app/solve_command.cpp) while the other ranks
/// skip it and wait at the job's end. Only rank 0 may hold one.
class RootAlone {
 public:
  RootAlone();
  ~RootAlone();
  RootAlone(const RootAlone &) = delete;
  RootAlone &operator=(const RootAlone &) = delete;
};

/// Ends the whole job at once (an error on one rank, which the others,
/// waiting in a collective, would never hear of); never returns.
[[noreturn]] void abortAll(int exitStatus);

/// Bytes this rank has handed to the sums so far (each array once): the
/// communication volume of a run, for docs/PERFORMANCE.md's model.
uint64_t bytesSummed();

/// "rank 2 of 4" for messages, empty with one rank.
std::string rankLabel();

}  // namespace radiant::cluster
