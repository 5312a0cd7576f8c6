#include "image_method_command.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>

#include "display_options.h"
#include "io/image.h"
#include "util/interrupt.h"

namespace radiant {

std::string passOutputPath(const std::string &path, int pass) {
  std::filesystem::path p(path);
  return (p.parent_path() / (p.stem().string() + fmt::format(".pass{}", pass) + p.extension().string())).string();
}

void runImageMethod(const RendererInfo &method, const Parameters &parameters, ImageJob job,
                    const ImageMethodCommand &command) {
  job.output = [&](int pass, const std::string &summary, const Image &mean, const Image &variance) {
    // A pass cut short by Ctrl-C is not an image of its pass: the last complete one stands.
    if (interruptRequested()) return;
    std::vector<std::string> paths;
    for (const std::string &path : command.outputs) paths.push_back(passOutputPath(path, pass));
    for (const std::string &path : command.outputs) paths.push_back(path);  // the latest pass
    Image image = mean;
    writeRenderOutputs(image, paths, command.display, command.describeDisplay && pass == 1, job.tracer, job.camera,
                       true);
    if (!command.variancePath.empty()) writeImage(variance, command.variancePath);
    if (!command.quiet) fmt::print(stderr, "radiant: {}; wrote {}\n", summary, fmt::join(paths, ", "));
  };
  if (!command.quiet) job.progress = [](const std::string &label) { return makeConsoleProgress(label); };
  method.render(job, parameters);
}

}  // namespace radiant
