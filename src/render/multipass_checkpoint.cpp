#include "render/multipass_checkpoint.h"

#include <cmath>
#include <cstring>
#include <fstream>

#include "render/checkpoint_io.h"
#include "util/atomic_file.h"
#include "util/input_file.h"

namespace radiant {

namespace {

constexpr char kMultipassCheckpointMagic[] = "RADIANT-MULTIPASS";
constexpr uint32_t kMultipassCheckpointVersion = 1;

}  // namespace

void writeMultipassCheckpoint(const std::string &path, const MultipassCheckpoint &c,
                              const ControlVariateImage &combined) {
  writeAtomically(path, [&](const std::string &temporary) {
    std::ofstream out(temporary, std::ios::binary);
    if (!out) throw std::runtime_error("cannot open the temporary file");
    CheckpointWriter w(out);
    writeCheckpointHeader(w, kMultipassCheckpointMagic, kMultipassCheckpointVersion, c.job);
    const Film &controls = combined.controlSums();
    const PairedFilm &pairs = combined.pairedSums();
    w.value(int32_t(controls.width)), w.value(int32_t(controls.height)), w.value(int32_t(kBandCount));
    w.value(int32_t(c.pass)), w.value(uint8_t(c.paired)), w.value(int32_t(c.samplesPerPixel));
    w.value(uint8_t(c.previewSolution)), w.value(c.elapsedSeconds);
    w.value(c.unitsSpent), w.value(c.controlSpent), w.value(c.pairedSpent), w.value(c.controlCost);
    w.value(c.pairedCost);
    w.value(int32_t(combined.controlSamples())), w.value(int32_t(combined.pairedSamples()));
    w.array(controls.sum), w.array(controls.sumSquares), w.array(controls.samples);
    w.array(pairs.sumControl), w.array(pairs.sumControlSquares), w.array(pairs.sumDifference);
    w.array(pairs.sumDifferenceSquares), w.array(pairs.sumProducts), w.array(pairs.samples);
    out.flush();
    if (!out) throw std::runtime_error("write failed (disk full?)");
  });
}

MultipassCheckpoint readMultipassCheckpoint(const std::string &path, const std::string &job, int width, int height) {
  // Checked first: opening a FIFO by name would block until something wrote to it.
  if (const InputFileRead file = checkInputFile(path); !file.ok())
    throw InputError(InputLocation{path}, inputFileProblem(file, "the checkpoint '" + path + "'"));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(InputLocation{path}, "cannot open the checkpoint");
  CheckpointReader r(in, path, "multipass checkpoint");
  readCheckpointHeader(r, kMultipassCheckpointMagic, kMultipassCheckpointVersion, job);
  MultipassCheckpoint c;
  c.job = job;
  const int w = r.value<int32_t>("the header"), h = r.value<int32_t>("the header");
  const int bands = r.value<int32_t>("the header");
  if (w != width || h != height || bands != kBandCount)
    r.fail(fmt::format("it holds a {}x{} image of {} bands, the render is {}x{} of {}", w, h, bands, width, height,
                       kBandCount));
  c.pass = r.value<int32_t>("the header");
  c.paired = r.value<uint8_t>("the header") != 0;
  c.samplesPerPixel = r.value<int32_t>("the header");
  c.previewSolution = r.value<uint8_t>("the header") != 0;
  c.elapsedSeconds = r.value<double>("the header");
  for (double *v : {&c.unitsSpent, &c.controlSpent, &c.pairedSpent, &c.controlCost, &c.pairedCost})
    *v = r.value<double>("the schedule");
  c.sums.controlSpp = r.value<int32_t>("the sample counts");
  c.sums.pairedSpp = r.value<int32_t>("the sample counts");
  bool finite = std::isfinite(c.elapsedSeconds) && c.elapsedSeconds >= 0;
  for (double v : {c.unitsSpent, c.controlSpent, c.pairedSpent, c.controlCost, c.pairedCost})
    finite = finite && std::isfinite(v) && v >= 0;
  if (c.pass < 3 || c.samplesPerPixel < 1 || !finite || c.sums.pairedSpp < 0 || c.sums.controlSpp < c.sums.pairedSpp)
    r.fail("its header holds impossible counts");
  c.sums.controls = Film(width, height);
  c.sums.pairs = PairedFilm(width, height);
  Film &controls = c.sums.controls;
  PairedFilm &pairs = c.sums.pairs;
  r.array(controls.sum, "the film"), r.array(controls.sumSquares, "the film"), r.array(controls.samples, "the film");
  for (std::vector<Bands> *v : {&pairs.sumControl, &pairs.sumControlSquares, &pairs.sumDifference,
                                &pairs.sumDifferenceSquares, &pairs.sumProducts})
    r.array(*v, "the paired film");
  r.array(pairs.samples, "the paired film");
  if (!r.atEnd()) r.fail("it has bytes after the films");
  return c;
}

}  // namespace radiant
