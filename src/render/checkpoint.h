// A render's checkpoint: everything the driver needs to carry on after the
// process was stopped (killed, a cluster job's time limit, Ctrl-C) and end
// with the very pixels of a run that never stopped.
//
// The driver (render/driver.h) saves one every few seconds between waves of
// tiles, and once more when interrupted: the film's sums, the round in
// progress and which of its tiles are complete, the pixels that have
// converged, the time spent. Each pixel's samples are numbered and drawn
// from their own generator (render/sampler.h), so a resumed run that redoes
// the round's unfinished tiles adds exactly the samples the uninterrupted
// run would have, in the same order.
//
// The file is binary, host byte order, written atomically (a temporary file,
// then a rename: a kill during the write leaves the previous checkpoint). It
// records the job it belongs to (`job`: the scene's and options' fingerprint,
// made by the command line) and is refused for any other.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "render/film.h"

namespace radiant {

struct RenderCheckpoint {
  std::string job;      ///< fingerprint of the scene and options; must match to resume
  int tileSize = 0;     ///< the driver's tiles, so the tile flags mean the same tiles
  int samplesDone = 0;  ///< complete rounds: samples every active pixel has
  int roundEnd = 0;     ///< the round in progress takes samples samplesDone … roundEnd − 1 (= samplesDone: none)
  double elapsedSeconds = 0;      ///< render time before this checkpoint, for a time budget
  uint64_t cameraSamples = 0;     ///< camera samples taken in complete rounds
  std::vector<uint8_t> tileDone;  ///< per tile: complete in the round in progress
  std::vector<uint8_t> active;    ///< per pixel: still taking samples (render/driver.h, converged pixels)
};

/// Writes the checkpoint and the film (atomically; std::runtime_error naming the file on failure).
void writeRenderCheckpoint(const std::string &path, const RenderCheckpoint &checkpoint, const Film &film);

/// Reads a checkpoint into `checkpoint` and `film` (which must be sized, with
/// its channels named, as the render's: the file must agree). InputError
/// naming the file and what is wrong for a file that is not a checkpoint,
/// is truncated, or belongs to another job or image size.
void readRenderCheckpoint(const std::string &path, const std::string &job, RenderCheckpoint &checkpoint, Film &film);

}  // namespace radiant
