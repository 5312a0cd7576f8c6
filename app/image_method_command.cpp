#include "image_method_command.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>

#include "cluster/cluster.h"
#include "display_options.h"
#include "io/image.h"
#include "util/atomic_file.h"
#include "util/file_extension.h"
#include "util/interrupt.h"

namespace radiant {

void runImageMethod(const RendererInfo &method, const Parameters &parameters, ImageJob job,
                    const ImageMethodCommand &command) {
  std::vector<float> coverage;  // the emitters in view: the same camera for every pass
  job.output = [&](int pass, const std::string &summary, const Image &mean, const Image &variance) {
    // A pass cut short by Ctrl-C is not an image of its pass: the last complete one stands.
    // With several MPI ranks rank 0 writes (every rank has the whole image: render/driver.h).
    if (interruptRequested() || !cluster::isRoot()) return;
    std::vector<std::string> passPaths, paths;
    for (const std::string &path : command.outputs) passPaths.push_back(passFilePath(path, pass));
    Image image = mean;
    writeRenderOutputs(image, passPaths, command.display, command.describeDisplay && pass == 1, job.tracer, job.camera,
                       true, &coverage);
    // The latest pass: a copy of its files, not a second encoding (a pass's time counts in --time).
    for (size_t i = 0; i < passPaths.size(); ++i)
      writeAtomically(command.outputs[i], [&](const std::string &temporary) {
        std::filesystem::copy_file(passPaths[i], temporary, std::filesystem::copy_options::overwrite_existing);
      });
    paths = passPaths;
    paths.insert(paths.end(), command.outputs.begin(), command.outputs.end());
    if (!command.variancePath.empty()) writeImage(variance, command.variancePath);
    if (!command.quiet) fmt::print(stderr, "radiant: {}; wrote {}\n", summary, fmt::join(paths, ", "));
  };
  if (!command.quiet) job.progress = [](const std::string &label) { return makeConsoleProgress(label); };
  method.render(job, parameters);
}

}  // namespace radiant
