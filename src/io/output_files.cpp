#include "io/output_files.h"

#include <unistd.h>

#include <filesystem>

namespace radiant {

namespace fs = std::filesystem;

namespace {

/// The path as the file system resolves it (symbolic links and ".." followed
/// as far as they exist), so that "a.exr" and "./dir/../a.exr" compare equal.
fs::path resolved(const std::string &path) {
  std::error_code ec;
  fs::path absolute = fs::absolute(path, ec);
  if (ec) return fs::path(path).lexically_normal();
  fs::path canonical = fs::weakly_canonical(absolute, ec);
  return ec ? absolute.lexically_normal() : canonical;
}

}  // namespace

void checkOutputFiles(const std::vector<OutputFile> &outputs, const std::vector<std::string> &inputs) {
  std::vector<fs::path> seen;
  for (const OutputFile &output : outputs) {
    const std::string &path = output.path;
    auto fail = [&](const std::string &why) { throw InputError(output.from, "cannot write '" + path + "': " + why); };
    if (path.empty()) throw InputError(output.from, "the output file name is empty");
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (fs::is_directory(status)) fail("it is a folder; give a file name inside it");
    if (fs::exists(status) && !fs::is_regular_file(status))
      fail("it exists and is not a regular file (a device or a pipe would be replaced)");
    fs::path folder = fs::path(path).parent_path();
    if (folder.empty()) folder = ".";
    if (!fs::is_directory(folder, ec)) fail("the folder '" + folder.string() + "' does not exist");
    if (::access(folder.c_str(), W_OK | X_OK) != 0)
      fail("no permission to write in the folder '" + folder.string() + "'");
    const fs::path here = resolved(path);
    for (const std::string &input : inputs)
      if (!input.empty() && resolved(input) == here) fail("it is an input of this command and would be overwritten");
    for (size_t i = 0; i < seen.size(); ++i)
      if (seen[i] == here) fail("it is given twice (also as '" + outputs[i].path + "')");
    seen.push_back(here);
  }
}

}  // namespace radiant
