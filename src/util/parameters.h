// A method's parameters: the table it declares and the values a user gave.
//
// Every registry entry (renderers, solvers) carries a table of ParameterSpec:
// name, type, default, range and one line of documentation. The command line
// builds its flags and its --help groups from the tables, docs/cli.md's
// option tables are generated from them, and a value given for a parameter
// the chosen method does not declare is an error naming the methods that do
// (pbrt-v4's ParameterDictionary::ReportUnused, Mitsuba 3's unqueried
// properties). A default is written once, in the table.
//
// The library knows no command line: a given value carries the InputLocation
// its caller says it came from ("--sources", a JSON path, …), and errors name that.
#pragma once

#include <limits>
#include <map>
#include <string>
#include <vector>

#include "util/error.h"

namespace radiant {

enum class ParameterType { Flag, Integer, Real, Choice };

/// A minimum meaning "greater than 0" (describeRange writes "> 0").
constexpr double kPositive = std::numeric_limits<double>::denorm_min();

struct ParameterSpec {
  std::string name;  ///< lower-case words joined by '-': "sources", "selective-threshold"
  ParameterType type = ParameterType::Real;
  std::string defaultValue;  ///< as text ("4", "0.1", "mc"; a flag's is "false")
  std::string documentation;
  double minimum = -std::numeric_limits<double>::infinity();  ///< Integer, Real: inclusive
  double maximum = std::numeric_limits<double>::infinity();
  /// Choice: the values allowed. Integer, Real: words allowed besides numbers
  /// (exposure's "auto"); Parameters::text tells them apart.
  std::vector<std::string> choices;
  /// The default is written in words ("1/8 of the scene's extent") because it
  /// depends on the scene; defaultValue is then empty and given() tells.
  std::string defaultDescription;
  /// A parameter this one cannot be given with ("source-fraction" excludes "sources").
  std::string excludes;
  /// Integer: the value must be a multiple of this (2: even), checked with
  /// the range when the command line is read, before any solve; 0 for any.
  int multipleOf = 0;

  /// "4", "0.1 (0…1)", "mc (point, mc)": the default and what is allowed, for help and docs.
  std::string describeDefault() const;
  std::string describeRange() const;
};

using ParameterTable = std::vector<ParameterSpec>;

/// Values given by name, each with where it came from.
class ParameterValues {
 public:
  void set(const std::string &name, std::string text, InputLocation origin);
  bool has(const std::string &name) const { return values_.count(name) > 0; }
  struct Given {
    std::string text;
    InputLocation origin;
  };
  const std::map<std::string, Given> &all() const { return values_; }

 private:
  std::map<std::string, Given> values_;
};

/// One method's view: its table and the given values. Reading a parameter
/// returns the given value or the table's default; reading one the table
/// does not declare is a programming error (std::logic_error).
class Parameters {
 public:
  Parameters() = default;
  Parameters(const ParameterTable &table, ParameterValues given);

  bool flag(const std::string &name) const;
  long long integer(const std::string &name) const;
  double real(const std::string &name) const;
  std::string choice(const std::string &name) const;
  /// The value as given, or the default, as text (a numeric parameter's word, such as "auto").
  std::string text(const std::string &name) const { return text(spec(name)); }
  /// Whether a value was given (for parameters whose default depends on the scene).
  bool given(const std::string &name) const;
  /// Where the given value came from, for errors found later (by the method).
  InputLocation origin(const std::string &name) const;
  /// The values as given (a method that runs others passes them on).
  const ParameterValues &givenValues() const { return given_; }

 private:
  const ParameterSpec &spec(const std::string &name) const;
  std::string text(const ParameterSpec &spec) const;

  const ParameterTable *table_ = nullptr;
  ParameterValues given_;
};

/// Checks `given` against `table` before any work: each value parses as its
/// type and lies in its range or choices; a name the table does not declare
/// is an InputError at its origin saying that `owner` ("--method kok") does
/// not use it and which of `others` (name → table) do, or suggesting the
/// closest known name.
void checkParameters(const ParameterTable &table, const ParameterValues &given, const std::string &owner,
                     const std::vector<std::pair<std::string, const ParameterTable *>> &others);

/// Parses `text` as the spec's type and checks its range: the value as a
/// double (flags 0 or 1; choices their index), or an InputError at `origin`.
double parseParameter(const ParameterSpec &spec, const std::string &text, const InputLocation &origin);

}  // namespace radiant
