#include "radiosity/solve_checkpoint.h"

#include <fmt/format.h>

#include <cstring>
#include <fstream>
#include <stdexcept>

#include "util/atomic_file.h"
#include "util/error.h"

namespace radiant {

namespace {

constexpr char kSolveCheckpointMagic[] = "RADIANT-SOLVE-CHECKPOINT";
constexpr uint32_t kSolveCheckpointVersion = 2;
constexpr uint32_t kMaxJob = 1 << 20;

static_assert(sizeof(Bands) == kBandCount * sizeof(double), "Bands are written as kBandCount doubles");

template <typename State, typename Visit>
void forEachStateArray(State &state, const Visit &visit) {
  for (auto *v : {&state.radiosity, &state.direct, &state.indirect, &state.unshot, &state.irradiance}) visit(*v);
}

}  // namespace

void writeStochasticCheckpoint(const std::string &path, const std::string &job, const StochasticCheckpoint &state) {
  if (state.raysArrived.size() != state.radiosity.size())
    throw std::logic_error("a solve checkpoint needs the rays of every element");
  writeAtomically(path, [&](const std::string &temporary) {
    std::ofstream out(temporary, std::ios::binary);
    if (!out) throw std::runtime_error("cannot open the temporary file");
    auto put = [&](const auto &v) { out.write(reinterpret_cast<const char *>(&v), sizeof v); };
    out.write(kSolveCheckpointMagic, sizeof kSolveCheckpointMagic - 1);
    put(kSolveCheckpointVersion);
    put(uint32_t(job.size()));
    out.write(job.data(), std::streamsize(job.size()));
    put(uint64_t(state.radiosity.size())), put(int32_t(kBandCount));
    put(int32_t(state.iteration)), put(uint8_t(state.emissionFirst)), put(state.formFactorRays), put(state.seconds);
    put(uint8_t(!state.lightGain.empty())), put(uint8_t(!state.transmittedDirect.empty()));
    auto array = [&](const auto &v) {
      out.write(reinterpret_cast<const char *>(v.data()), std::streamsize(v.size() * sizeof(v[0])));
    };
    forEachStateArray(state, array);
    if (!state.lightGain.empty()) array(state.lightGain);
    if (!state.transmittedDirect.empty()) array(state.transmittedDirect), array(state.transmittedIndirect);
    array(state.raysArrived);
    out.flush();
    if (!out) throw std::runtime_error("write failed (disk full?)");
  });
}

StochasticCheckpoint readStochasticCheckpoint(const std::string &path, const std::string &job, size_t elements) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(InputLocation{path}, "cannot open the solve checkpoint");
  auto fail = [&](const std::string &message) {
    throw InputError(InputLocation{path}, "not a usable solve checkpoint: " + message);
  };
  auto bytes = [&](void *data, size_t size, const char *what) {
    if (!in.read(static_cast<char *>(data), std::streamsize(size)))
      fail(fmt::format("the file ends inside {} (truncated?)", what));
  };
  auto get = [&](auto &v, const char *what) { bytes(&v, sizeof v, what); };
  char magic[sizeof kSolveCheckpointMagic - 1];
  bytes(magic, sizeof magic, "the header");
  if (std::memcmp(magic, kSolveCheckpointMagic, sizeof magic) != 0)
    fail("it does not start with RADIANT-SOLVE-CHECKPOINT");
  uint32_t version = 0, jobSize = 0;
  get(version, "the header");
  if (version != kSolveCheckpointVersion)
    fail(fmt::format("checkpoint version {}; this radiant reads version {}", version, kSolveCheckpointVersion));
  get(jobSize, "the header");
  if (jobSize > kMaxJob) fail("its job description is too long");
  std::string saved(jobSize, '\0');
  bytes(saved.data(), jobSize, "the job description");
  if (saved != job)
    fail("it belongs to another job (a different scene file, solver, option or seed); remove it to start afresh");
  uint64_t count = 0;
  int32_t bands = 0, iteration = 0;
  uint8_t emissionFirst = 0, hasLightGain = 0, hasTransmitted = 0;
  StochasticCheckpoint state;
  get(count, "the header"), get(bands, "the header"), get(iteration, "the header");
  get(emissionFirst, "the header"), get(state.formFactorRays, "the header"), get(state.seconds, "the header");
  get(hasLightGain, "the header"), get(hasTransmitted, "the header");
  if (count != elements || bands != kBandCount)
    fail(fmt::format("it holds {} elements of {} bands, the mesh has {} of {}", count, bands, elements, kBandCount));
  if (iteration < 0 || emissionFirst > 1 || hasLightGain > 1 || hasTransmitted > 1 || !(state.seconds >= 0))
    fail("its header holds impossible values");
  state.iteration = iteration;
  state.emissionFirst = emissionFirst != 0;
  auto array = [&](auto &v) {
    v.resize(elements);
    bytes(v.data(), elements * sizeof(v[0]), "the element values");
  };
  forEachStateArray(state, array);
  if (hasLightGain) array(state.lightGain);
  if (hasTransmitted) array(state.transmittedDirect), array(state.transmittedIndirect);
  array(state.raysArrived);
  if (in.peek() != std::char_traits<char>::eof()) fail("it has bytes after the element values");
  return state;
}

}  // namespace radiant
