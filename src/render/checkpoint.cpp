#include "render/checkpoint.h"

#include <fmt/format.h>

#include <cstring>
#include <fstream>

#include "render/checkpoint_io.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/input_file.h"

namespace radiant {

namespace {

constexpr char kRenderCheckpointMagic[] = "RADIANT-CHECKPOINT";
constexpr uint32_t kRenderCheckpointVersion = 1;
}  // namespace

void writeRenderCheckpoint(const std::string &path, const RenderCheckpoint &c, const Film &film) {
  writeAtomically(path, [&](const std::string &temporary) {
    std::ofstream out(temporary, std::ios::binary);
    if (!out) throw std::runtime_error("cannot open the temporary file");
    CheckpointWriter w(out);
    writeCheckpointHeader(w, kRenderCheckpointMagic, kRenderCheckpointVersion, c.job);
    w.value(int32_t(film.width)), w.value(int32_t(film.height)), w.value(int32_t(kBandCount));
    w.value(int32_t(c.tileSize)), w.value(int32_t(c.samplesDone)), w.value(int32_t(c.roundEnd));
    w.value(c.elapsedSeconds), w.value(c.cameraSamples);
    w.value(uint32_t(c.tileDone.size()));
    w.bytes(c.tileDone.data(), c.tileDone.size());
    w.bytes(c.active.data(), c.active.size());
    w.value(uint32_t(film.channels.size()));
    for (const FilmChannel &channel : film.channels) w.text(channel.name);
    forEachFilmArray(
        film, [&](const std::vector<Bands> &v) { w.bytes(v.data(), v.size() * sizeof(Bands)); },
        [&](const std::vector<uint32_t> &v) { w.bytes(v.data(), v.size() * sizeof(uint32_t)); });
    out.flush();
    if (!out) throw std::runtime_error("write failed (disk full?)");
  });
}

void readRenderCheckpoint(const std::string &path, const std::string &job, RenderCheckpoint &c, Film &film) {
  // Checked first: opening a FIFO by name would block until something wrote to it.
  if (const InputFileRead file = checkInputFile(path); !file.ok())
    throw InputError(InputLocation{path}, inputFileProblem(file, "the checkpoint '" + path + "'"));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(InputLocation{path}, "cannot open the checkpoint");
  CheckpointReader r(in, path);
  readCheckpointHeader(r, kRenderCheckpointMagic, kRenderCheckpointVersion, job);
  c.job = job;
  const int width = r.value<int32_t>("the header"), height = r.value<int32_t>("the header");
  const int bands = r.value<int32_t>("the header");
  if (width != film.width || height != film.height || bands != kBandCount)
    r.fail(fmt::format("it holds a {}x{} image of {} bands, the render is {}x{} of {}", width, height, bands,
                       film.width, film.height, kBandCount));
  c.tileSize = r.value<int32_t>("the header");
  c.samplesDone = r.value<int32_t>("the header");
  c.roundEnd = r.value<int32_t>("the header");
  c.elapsedSeconds = r.value<double>("the header");
  c.cameraSamples = r.value<uint64_t>("the header");
  if (c.tileSize < 1 || c.samplesDone < 0 || c.roundEnd < c.samplesDone || !(c.elapsedSeconds >= 0))
    r.fail("its header holds impossible counts");
  const uint32_t tiles = r.value<uint32_t>("the tile count");
  const size_t expectedTiles =
      size_t((width + c.tileSize - 1) / c.tileSize) * size_t((height + c.tileSize - 1) / c.tileSize);
  if (tiles != expectedTiles && tiles != 1)
    r.fail(fmt::format("it has {} tiles, a {}x{} image has {} of {} pixels", tiles, width, height, expectedTiles,
                       c.tileSize));
  c.tileDone.assign(tiles, 0);
  r.bytes(c.tileDone.data(), tiles, "the tile flags");
  c.active.assign(film.pixelCount(), 0);
  r.bytes(c.active.data(), c.active.size(), "the converged-pixel flags");
  const uint32_t channels = r.value<uint32_t>("the channel count");
  if (channels != film.channels.size())
    r.fail(fmt::format("it has {} film channels, the render {}", channels, film.channels.size()));
  for (const FilmChannel &channel : film.channels)
    if (const std::string name = r.text("a channel name"); name != channel.name)
      r.fail(fmt::format("it has film channel '{}' where the render has '{}'", name, channel.name));
  forEachFilmArray(
      film, [&](std::vector<Bands> &v) { r.bytes(v.data(), v.size() * sizeof(Bands), "the film"); },
      [&](std::vector<uint32_t> &v) { r.bytes(v.data(), v.size() * sizeof(uint32_t), "the film"); });
  if (!r.atEnd()) r.fail("it has bytes after the film");
}

}  // namespace radiant
