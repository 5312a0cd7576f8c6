// --checkpoint, --checkpoint-interval and --resume, as `render` and `solve`
// take them (docs/cluster.md), and the fingerprint of the inputs a
// checkpoint records (render/checkpoint.h, radiosity/solve_checkpoint.h).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace radiant {

struct CheckpointCommandOptions {
  std::string path;  ///< empty: no checkpoints
  double intervalSeconds = 10;
  bool resume = false;
};

/// The three flags; `state` says what is saved ("the render's state").
void addCheckpointOptions(CLI::App &app, CheckpointCommandOptions &options, const std::string &state);

/// --resume without --checkpoint, and an existing checkpoint without --resume
/// (a second run would overwrite the first one's state): InputError.
void checkCheckpointOptions(const CheckpointCommandOptions &options);

/// The same for the files a checkpoint is split into (a spectral pass's, a
/// render's solve): without --resume, any of them existing is an InputError.
void refuseExistingCheckpoints(const CheckpointCommandOptions &options, const std::vector<std::string> &files);

/// FNV-1a (64 bits) of the file's bytes, in hex; "" for no path, "unreadable" when it cannot be read.
std::string fileFingerprint(const std::string &path);

}  // namespace radiant
