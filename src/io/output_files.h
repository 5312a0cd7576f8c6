// The files a command will write, checked before any work starts: a render of
// minutes must not end in "cannot write 'missing/dir/x.exr'", and one output
// must not fail after another has been written. Every writer then goes through
// a temporary file and a rename (util/atomic_file.h), so a failure leaves no
// partial file.
#pragma once

#include <string>
#include <vector>

#include "util/error.h"

namespace radiant {

struct OutputFile {
  std::string path;
  InputLocation from;  ///< the flag or key that named it, for messages
};

/// Throws InputError at an output's origin when: its path is empty or is a
/// folder or another non-regular file (a device, a pipe: the rename would
/// replace it); its folder does not exist or cannot be written in; two outputs
/// are the same file; or an output is one of `inputs` (the scene, a solution)
/// it would overwrite.
void checkOutputFiles(const std::vector<OutputFile> &outputs, const std::vector<std::string> &inputs = {});

}  // namespace radiant
