// Command-line flags built from the registries' parameter tables
// (util/parameters.h): one flag per parameter name (--sources for
// "sources"), one --help group per method or solver, the default and range
// written once, in the table.
#pragma once

#include <CLI/CLI.hpp>
#include <map>
#include <string>
#include <vector>

#include "util/parameters.h"

namespace radiant {

/// A --help group: its title ("--method kok") and the parameters it lists.
struct ParameterGroup {
  std::string title;
  const ParameterTable *table;
};

/// A check for --seed: a decimal integer in 0 … 2⁶⁴ − 1 (CLI11 alone saturates
/// a larger one silently, and accepts "1e3" as 1000).
CLI::Validator seedRange();

class ParameterFlags {
 public:
  /// Adds a flag for every parameter of `groups` not added before, in the
  /// first group that declares it; the help of a parameter several groups
  /// declare says which ("also: multipass").
  void add(CLI::App &app, const std::vector<ParameterGroup> &groups);
  /// The values given on the command line, each located at its flag.
  ParameterValues given() const;

 private:
  struct Flag {
    std::string text;
    bool on = false;
    bool isFlag = false;
    CLI::Option *option = nullptr;
  };
  std::map<std::string, Flag> flags_;  ///< by parameter name; a map keeps the bound addresses
};

/// "--method kok" → "kok": the name a group's title ends with.
std::string groupOwner(const std::string &title);

}  // namespace radiant
