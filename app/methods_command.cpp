// radiant methods — the rendering methods and radiosity solvers, each with its
// parameters (their flags, defaults, ranges and meaning), from the registries'
// tables. `--markdown` prints the tables docs/cli.md includes; tests/cli_test.sh
// fails when the two drift apart.
#include <fmt/format.h>

#include "commands.h"
#include "display/tone_operator.h"
#include "radiosity/solver.h"
#include "render/registry.h"

namespace radiant {

namespace {

std::string escapeCell(const std::string &text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

void printTable(const ParameterTable &table, bool markdown) {
  if (table.empty()) {
    fmt::print("{}", markdown ? "No parameters of its own.\n\n" : "    (no parameters of its own)\n");
    return;
  }
  if (markdown) fmt::print("| flag | default | allowed | meaning |\n|---|---|---|---|\n");
  for (const ParameterSpec &spec : table) {
    const std::string flag = "--" + spec.name;
    const std::string value = spec.describeDefault().empty() ? "—" : spec.describeDefault();
    const std::string range = spec.describeRange().empty() ? "—" : spec.describeRange();
    if (markdown)
      fmt::print("| `{}` | {} | {} | {} |\n", flag, escapeCell(value), escapeCell(range),
                 escapeCell(spec.documentation));
    else
      fmt::print("    {:<24} default {}; {}{}\n", flag, value, spec.documentation,
                 range == "—" ? "" : " (" + range + ")");
  }
  if (markdown) fmt::print("\n");
}

}  // namespace

CommandRunner addMethodsCommand(CLI::App &app) {
  auto markdown = std::make_shared<bool>(false);
  app.add_flag("--markdown", *markdown, "Print Markdown tables (docs/cli.md includes them)");
  return [markdown]() {
    const bool md = *markdown;
    fmt::print("{}", md ? "### Parameters of each method (`radiant render --method NAME`)\n\n"
                        : "Rendering methods (--method):\n");
    for (const RendererInfo &info : rendererRegistry()) {
      fmt::print(fmt::runtime(md ? "#### `--method {}`\n\n{}.\n\n" : "  {}: {}\n"), info.name, info.summary);
      printTable(info.parameters, md);
    }
    fmt::print("{}", md ? "### Parameters of each solver (`--solver NAME`, for `solve` and the methods that read a "
                          "solution)\n\n"
                        : "\nRadiosity solvers (--solver):\n");
    std::vector<std::pair<std::string, std::string>> solvers = {
        {"auto", std::string(kAutoSolverSummary) + "; it takes the parameters of the solvers it may pick"}};
    for (const SolverInfo &info : solverRegistry()) solvers.push_back({info.name, info.summary});
    for (const auto &[name, summary] : solvers) {
      fmt::print(fmt::runtime(md ? "#### `--solver {}`\n\n{}.\n\n" : "  {}: {}\n"), name, summary);
      printTable(solverParameters(name), md);
    }
    fmt::print("{}", md ? "### Parameters of each tone operator (`--tonemap NAME`, for `tonemap` and `render`'s PNG "
                          "outputs)\n\n"
                        : "\nTone operators (--tonemap):\n");
    for (const ToneOperatorInfo &info : toneOperatorRegistry()) {
      fmt::print(fmt::runtime(md ? "#### `--tonemap {}`\n\n{}.\n\n" : "  {}: {}\n"), info.name, info.summary);
      printTable(info.parameters, md);
    }
    return 0;
  };
}

}  // namespace radiant
