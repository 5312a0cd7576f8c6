#include "checkpoint_options.h"

#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <fstream>

#include "util/error.h"
#include "util/input_file.h"

namespace radiant {

void addCheckpointOptions(CLI::App &app, CheckpointCommandOptions &o, const std::string &state) {
  app.add_option("--checkpoint", o.path,
                 "Save " + state +
                     " to this file every --checkpoint-interval seconds and when stopped (Ctrl-C, SIGTERM), so that "
                     "--resume carries on to the very result of an uninterrupted run (docs/cluster.md)");
  app.add_option("--checkpoint-interval", o.intervalSeconds, "Seconds between checkpoints")
      ->default_val(10)
      ->check(CLI::Range(0.0, 1e6));
  app.add_flag("--resume", o.resume,
               "Carry on from the --checkpoint file when it exists (else start): the same command and scene as the "
               "run that saved it");
}

void checkCheckpointOptions(const CheckpointCommandOptions &o) {
  if (o.resume && o.path.empty()) throw InputError(InputLocation{"--resume"}, "needs --checkpoint FILE");
  if (!o.path.empty()) refuseExistingCheckpoints(o, {o.path});
}

void refuseExistingCheckpoints(const CheckpointCommandOptions &o, const std::vector<std::string> &files) {
  if (o.resume) return;
  for (const std::string &file : files)
    if (std::filesystem::exists(file))
      throw InputError(InputLocation{"--checkpoint"},
                       "'" + file + "' exists: add --resume to carry on from it, or remove it");
}

std::string fileFingerprint(const std::string &path) {
  if (path.empty()) return "";
  if (!checkInputFile(path).ok()) return "unreadable";  // a FIFO would block the open below
  std::ifstream in(path, std::ios::binary);
  if (!in) return "unreadable";
  uint64_t hash = 0xcbf29ce484222325ULL;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    for (std::streamsize i = 0; i < in.gcount(); ++i) hash = (hash ^ uint8_t(buffer[i])) * 0x100000001b3ULL;
    if (!in) break;
  }
  return fmt::format("{:016x}", hash);
}

}  // namespace radiant
