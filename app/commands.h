// The subcommands of the `radiant` program. Each registers its options on a
// CLI11 subcommand and returns the function that runs it.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace radiant {

using CommandRunner = std::function<int()>;

CommandRunner addRenderCommand(CLI::App &app);
CommandRunner addCompareCommand(CLI::App &app);
CommandRunner addSolveCommand(CLI::App &app);
CommandRunner addTonemapCommand(CLI::App &app);
CommandRunner addMethodsCommand(CLI::App &app);
CommandRunner addExportCommand(CLI::App &app);
CommandRunner addServeCommand(CLI::App &app);
CommandRunner addInfoCommand(CLI::App &app);

}  // namespace radiant
