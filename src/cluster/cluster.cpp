#include "cluster/cluster.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdlib>
#include <stdexcept>
#include <thread>

#ifdef RADIANT_HAVE_MPI
#include <mpi.h>
#endif

namespace radiant::cluster {

namespace {

int worldRank = 0, worldSize = 1;
uint64_t summedBytes = 0;
bool rootAlone = false;  // a RootAlone lives: rank 0 works as one process
#ifdef RADIANT_HAVE_MPI
bool joined = false;

/// The collectives have other ranks to talk to.
bool sharing() {
  return joined && worldSize > 1 && !rootAlone;
}
#endif

/// Set by every launcher we know of: Open MPI's mpirun, PMIx (Slurm's srun
/// --mpi=pmix, prterun), PMI-1/2 (MPICH's hydra, srun --mpi=pmi2).
bool launchedByMpi() {
  for (const char *name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}

#ifdef RADIANT_HAVE_MPI
/// Waits for a non-blocking collective without taking a core from the ranks
/// still working. A blocking collective polls until the last rank arrives
/// (Open MPI spins, or calls sched_yield in a loop under
/// mpi_yield_when_idle): where ranks share cores, the first to arrive took
/// CPU from the others, and 3 ranks of a solve on 2 cores used 2.2 times one
/// process's CPU time, a third of it in the kernel. Here a rank polls for
/// 50 µs, then sleeps between polls, 20 µs doubling to 1 ms: a rank that
/// waits long costs almost nothing, and one that waits briefly loses at most
/// a millisecond. (The progress of the collective's own steps happens inside
/// MPI_Test.)
void waitQuietly(MPI_Request &request) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  auto pause = std::chrono::microseconds(20);
  for (;;) {
    int done = 0;
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    if (Clock::now() - start < std::chrono::microseconds(50)) continue;
    std::this_thread::sleep_for(pause);
    pause = std::min(2 * pause, std::chrono::microseconds(1000));
  }
}

/// MPI counts are ints: long arrays go in pieces of at most 2^30 elements.
template <typename T, typename Operation>
void inPieces(T *values, size_t count, const Operation &operation) {
  summedBytes += count * sizeof(T);
  constexpr size_t kPiece = size_t(1) << 30;
  for (size_t begin = 0; begin < count; begin += kPiece)
    operation(values + begin, static_cast<int>(std::min(kPiece, count - begin)));
}

template <typename T>
void allSum(T *values, size_t count, MPI_Datatype type) {
  if (!sharing()) return;
  inPieces(values, count, [&](T *piece, int n) {
    MPI_Request request;
    MPI_Iallreduce(MPI_IN_PLACE, piece, n, type, MPI_SUM, MPI_COMM_WORLD, &request);
    waitQuietly(request);
  });
}

template <typename T>
void rootSum(T *values, size_t count, MPI_Datatype type) {
  if (!sharing()) return;
  inPieces(values, count, [&](T *piece, int n) {
    MPI_Request request;
    if (worldRank == 0)
      MPI_Ireduce(MPI_IN_PLACE, piece, n, type, MPI_SUM, 0, MPI_COMM_WORLD, &request);
    else
      MPI_Ireduce(piece, nullptr, n, type, MPI_SUM, 0, MPI_COMM_WORLD, &request);
    waitQuietly(request);
  });
}
#endif

}  // namespace

Session::Session(int &argc, char **&argv) {
#ifdef RADIANT_HAVE_MPI
  if (!launchedByMpi()) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &worldRank);
  MPI_Comm_size(MPI_COMM_WORLD, &worldSize);
  joined = true;
#else
  (void)argc, (void)argv;
  if (launchedByMpi() && std::getenv("OMPI_COMM_WORLD_RANK") && std::string(std::getenv("OMPI_COMM_WORLD_RANK")) == "0")
    fmt::print(stderr,
               "radiant: warning: started by an MPI launcher, but this radiant was built without MPI: every "
               "process renders the whole job alone\n");
#endif
}

Session::~Session() {
#ifdef RADIANT_HAVE_MPI
  if (joined && worldSize > 1) {
    // The ranks end together here, while rank 0 may still be writing the
    // output: MPI_Finalize's own barrier would spin meanwhile.
    MPI_Request request;
    MPI_Ibarrier(MPI_COMM_WORLD, &request);
    waitQuietly(request);
  }
  if (joined) MPI_Finalize();
  joined = false;
  worldRank = 0, worldSize = 1;
#endif
}

int rank() {
  return worldRank;
}
int size() {
  return rootAlone ? 1 : worldSize;
}

RootAlone::RootAlone() {
  if (worldRank != 0) throw std::logic_error("cluster::RootAlone on rank " + std::to_string(worldRank));
  rootAlone = true;
}
RootAlone::~RootAlone() {
  rootAlone = false;
}

bool builtWithMpi() {
#ifdef RADIANT_HAVE_MPI
  return true;
#else
  return false;
#endif
}

#ifdef RADIANT_HAVE_MPI
void sumOnAllRanks(double *values, size_t count) {
  allSum(values, count, MPI_DOUBLE);
}
void sumOnAllRanks(int64_t *values, size_t count) {
  allSum(values, count, MPI_INT64_T);
}
void sumOnAllRanks(uint32_t *values, size_t count) {
  allSum(values, count, MPI_UINT32_T);
}
void sumOnAllRanks(uint8_t *values, size_t count) {
  allSum(values, count, MPI_UINT8_T);
}
void sumOnRoot(double *values, size_t count) {
  rootSum(values, count, MPI_DOUBLE);
}
void sumOnRoot(uint32_t *values, size_t count) {
  rootSum(values, count, MPI_UINT32_T);
}
void sumOnRoot(uint8_t *values, size_t count) {
  rootSum(values, count, MPI_UINT8_T);
}
std::vector<uint8_t> gatherFromAllRanks(const std::vector<uint8_t> &mine, std::vector<size_t> &starts) {
  starts.assign(size_t(size()) + 1, 0);
  if (!sharing()) {
    starts[1] = mine.size();
    return mine;
  }
  summedBytes += mine.size();
  // Each rank's byte count, then the bytes: MPI's counts are ints, so a
  // total beyond 2 GiB goes in rounds of at most 1 GiB from each rank.
  std::vector<uint64_t> counts(size_t(worldSize), 0);
  const uint64_t own = mine.size();
  MPI_Request request;
  MPI_Iallgather(&own, 1, MPI_UINT64_T, counts.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD, &request);
  waitQuietly(request);
  for (int r = 0; r < worldSize; ++r) starts[size_t(r) + 1] = starts[size_t(r)] + counts[size_t(r)];
  std::vector<uint8_t> all(starts.back());
  constexpr uint64_t kRound = uint64_t(1) << 30;
  const uint64_t largest = *std::max_element(counts.begin(), counts.end());
  std::vector<int> roundCounts(static_cast<size_t>(worldSize)), displacements(static_cast<size_t>(worldSize));
  std::vector<uint8_t> received;
  for (uint64_t offset = 0; offset < largest; offset += kRound) {
    // This round's piece of each rank's bytes, laid out one after another.
    int total = 0;
    for (int r = 0; r < worldSize; ++r) {
      const uint64_t left = counts[size_t(r)] > offset ? counts[size_t(r)] - offset : 0;
      roundCounts[size_t(r)] = int(std::min(left, kRound));
      displacements[size_t(r)] = total;
      total += roundCounts[size_t(r)];
    }
    received.resize(size_t(total));
    MPI_Iallgatherv(mine.data() + std::min<uint64_t>(offset, own), roundCounts[size_t(worldRank)], MPI_BYTE,
                    received.data(), roundCounts.data(), displacements.data(), MPI_BYTE, MPI_COMM_WORLD, &request);
    waitQuietly(request);
    for (int r = 0; r < worldSize; ++r)
      std::copy_n(received.data() + displacements[size_t(r)], roundCounts[size_t(r)],
                  all.data() + starts[size_t(r)] + offset);
  }
  return all;
}
template <typename T>
T broadcastFromRoot(T value, MPI_Datatype type) {
  if (!sharing()) return value;
  MPI_Request request;
  MPI_Ibcast(&value, 1, type, 0, MPI_COMM_WORLD, &request);
  waitQuietly(request);
  return value;
}
int64_t fromRoot(int64_t value) {
  return broadcastFromRoot(value, MPI_INT64_T);
}
double fromRoot(double value) {
  return broadcastFromRoot(value, MPI_DOUBLE);
}
bool anyRank(bool value) {
  int v = value ? 1 : 0;
  if (sharing()) {
    MPI_Request request;
    MPI_Iallreduce(MPI_IN_PLACE, &v, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD, &request);
    waitQuietly(request);
  }
  return v != 0;
}
void abortAll(int exitStatus) {
  if (joined && worldSize > 1) MPI_Abort(MPI_COMM_WORLD, exitStatus);
  std::exit(exitStatus);
}
#else
void sumOnAllRanks(double *, size_t) {}
void sumOnAllRanks(int64_t *, size_t) {}
void sumOnAllRanks(uint32_t *, size_t) {}
void sumOnAllRanks(uint8_t *, size_t) {}
void sumOnRoot(double *, size_t) {}
void sumOnRoot(uint32_t *, size_t) {}
void sumOnRoot(uint8_t *, size_t) {}
std::vector<uint8_t> gatherFromAllRanks(const std::vector<uint8_t> &mine, std::vector<size_t> &starts) {
  starts = {0, mine.size()};
  return mine;
}
int64_t fromRoot(int64_t value) {
  return value;
}
double fromRoot(double value) {
  return value;
}
bool anyRank(bool value) {
  return value;
}
void abortAll(int exitStatus) {
  std::exit(exitStatus);
}
#endif

uint64_t bytesSummed() {
  return summedBytes;
}

std::string rankLabel() {
  return worldSize > 1 ? fmt::format("rank {} of {}", worldRank, worldSize) : std::string();
}

}  // namespace radiant::cluster
