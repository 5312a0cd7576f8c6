// A multipass render's checkpoint (render/multipass.h; docs/cluster.md):
// what its passes 3… have summed and how far their schedule got, saved at
// the start of every such pass with the plan of that pass. The pass in
// progress checkpoints its own film beside it (render/checkpoint.h), in
// FILE's stem + ".passK", so a resumed multipass render finishes that pass
// from where it stopped and then plans the rest as the uninterrupted run
// did: without a time budget, the same passes and the same final pixels.
//
// Passes 1 and 2 (the previews) are not saved: a run stopped in them starts
// again; one resumed after them does not redo them (their images are on disk).
// Binary, host byte order, written atomically; it records its job and is
// refused for any other.
#pragma once

#include <string>

#include "render/control_variate.h"

namespace radiant {

struct MultipassCheckpoint {
  std::string job;               ///< the command's fingerprint; must match to resume
  int pass = 3;                  ///< the pass in progress (its plan below)
  bool paired = true;            ///< its kind: paired samples, or controls only
  int samplesPerPixel = 0;       ///< its length
  bool previewSolution = false;  ///< passes 3… read the preview's solution (a short budget)
  double elapsedSeconds = 0;     ///< the render's time when the pass started
  /// The schedule's account (render/multipass.cpp): work units spent, and
  /// time (or units) spent on each kind and per sample of each kind.
  double unitsSpent = 0, controlSpent = 0, pairedSpent = 0, controlCost = 0, pairedCost = 0;
  ControlVariateImage::Sums sums;  ///< passes 3 … pass − 1
};

/// Writes it atomically (std::runtime_error naming the file on failure).
void writeMultipassCheckpoint(const std::string &path, const MultipassCheckpoint &checkpoint,
                              const ControlVariateImage &combined);

/// Reads one saved for `job` at width × height; InputError naming the file
/// and what is wrong for any other file, a truncated one or another job's.
MultipassCheckpoint readMultipassCheckpoint(const std::string &path, const std::string &job, int width, int height);

}  // namespace radiant
