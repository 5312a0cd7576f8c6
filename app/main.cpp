// radiant — command-line entry point. Catches the one error type (InputError)
// once, prints it and exits non-zero. Under mpirun every rank runs this
// (cluster/cluster.h); an error on any rank ends the whole job, since the
// others may be waiting for it in a collective.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>

#include "cluster/cluster.h"
#include "commands.h"
#include "interrupt_handler.h"
#include "scene/json_reader.h"
#include "util/error.h"
#include "util/interrupt.h"

namespace {

/// After "The following argument was not expected: --sorces": the command's
/// closest flag, for a typo (its flags include every method's parameters).
void suggestFlags(CLI::App &app, CLI::App &command) {
  std::vector<std::string> names;
  auto collect = [&](CLI::App &a) {
    for (const CLI::Option *option : a.get_options())
      for (const std::string &name : option->get_lnames()) names.push_back("--" + name);
  };
  collect(command);
  for (CLI::App *group : command.get_subcommands([](CLI::App *a) { return a->get_name().empty(); })) collect(*group);
  std::vector<std::string> unexpected = command.remaining();
  for (const std::string &arg : app.remaining()) unexpected.push_back(arg);
  for (const std::string &arg : unexpected) {
    if (arg.rfind("--", 0) != 0) continue;
    const std::string best = radiant::closestName(arg.substr(0, arg.find('=')), names);
    if (!best.empty()) fmt::print(stderr, "radiant: {}: did you mean {}?\n", arg, best);
  }
}

/// Prints an error (rank 0; another rank names itself) and, with several
/// ranks, ends the whole job: the others may wait for this one forever.
int fail(int status, const std::string &message) {
  namespace cluster = radiant::cluster;
  if (cluster::isRoot())
    fmt::print(stderr, "radiant: error: {}\n", message);
  else
    fmt::print(stderr, "radiant ({}): error: {}\n", cluster::rankLabel(), message);
  if (cluster::distributed()) {
    std::fflush(stderr);
    cluster::abortAll(status);
  }
  return status;
}

}  // namespace

int main(int argc, char **argv) {
  // Joins the MPI job when started by mpirun or srun (docs/cluster.md).
  radiant::cluster::Session cluster(argc, argv);
  CLI::App app{"Radiant — a global-illumination renderer built around radiosity (Cohen & Wallace, ch. 9)", "radiant"};
  app.set_version_flag("--version", std::string("radiant ") + RADIANT_VERSION +
                                        (radiant::cluster::builtWithMpi() ? " (MPI)" : " (no MPI)"));
  app.require_subcommand(1);
  CLI::App *render = app.add_subcommand("render", "Render a scene (JSON or OBJ) to EXR/PFM/PNG images");
  CLI::App *solve = app.add_subcommand("solve", "Compute a scene's radiosity solution, report it, save it for render");
  CLI::App *compare = app.add_subcommand("compare", "Compare an image with a reference: mean ratio, RMSE, relMSE");
  CLI::App *tonemap =
      app.add_subcommand("tonemap", "Map a linear image (EXR/PFM) to a display PNG or a false-colour luminance map");
  CLI::App *methods =
      app.add_subcommand("methods", "List the rendering methods and radiosity solvers with their parameters");
  CLI::App *exportCommand = app.add_subcommand(
      "export", "Write the radiosity solution as a mesh with light at its vertices: glTF 2.0 (.glb, .gltf) or PLY");
  CLI::App *serve =
      app.add_subcommand("serve", "Serve the browser viewer and a .glb on a local web server (127.0.0.1)");
  CLI::App *info = app.add_subcommand(
      "info", "Describe a scene as Radiant reads it: bounds and units, counts, what loading dropped, the solver");
  radiant::CommandRunner runRender = radiant::addRenderCommand(*render);
  radiant::CommandRunner runSolve = radiant::addSolveCommand(*solve);
  radiant::CommandRunner runCompare = radiant::addCompareCommand(*compare);
  radiant::CommandRunner runTonemap = radiant::addTonemapCommand(*tonemap);
  radiant::CommandRunner runMethods = radiant::addMethodsCommand(*methods);
  radiant::CommandRunner runExport = radiant::addExportCommand(*exportCommand);
  radiant::CommandRunner runServe = radiant::addServeCommand(*serve);
  radiant::CommandRunner runInfo = radiant::addInfoCommand(*info);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError &e) {
    // --help and --version exit 0; a bad flag is bad input, exit 2 like every other.
    const int status = app.exit(e);
    if (dynamic_cast<const CLI::ExtrasError *>(&e))
      for (CLI::App *command : {render, solve, compare, tonemap, methods, exportCommand, serve, info})
        if (command->parsed()) suggestFlags(app, *command);
    return status == 0 ? 0 : 2;
  }
  try {
    if (render->parsed()) return runRender();
    if (solve->parsed()) return runSolve();
    if (compare->parsed()) return runCompare();
    if (tonemap->parsed()) return runTonemap();
    if (methods->parsed()) return runMethods();
    if (exportCommand->parsed()) return runExport();
    if (serve->parsed()) return runServe();
    if (info->parsed()) return runInfo();
  } catch (const radiant::Interrupted &) {
    if (radiant::cluster::isRoot())
      fmt::print(stderr, "radiant: interrupted before anything was complete; nothing written\n");
    if (radiant::cluster::distributed()) radiant::cluster::abortAll(radiant::interruptedExitStatus());
    return radiant::interruptedExitStatus();
  } catch (const radiant::InputError &e) {
    // The library names a parameter ("mesh-size"); here it is a flag.
    const radiant::InputLocation &where = e.location();
    if (where.file.empty() && !where.parameter.empty()) return fail(2, "--" + where.parameter + ": " + e.message());
    return fail(2, e.what());
  } catch (const std::exception &e) {
    return fail(1, e.what());
  }
  return 0;
}
