#include "util/parameters.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace radiant {

namespace {

std::string joinNames(const std::vector<std::string> &names) {
  std::string joined;
  for (const std::string &n : names) joined += (joined.empty() ? "" : ", ") + n;
  return joined;
}

std::string formatBound(double v) {
  if (std::isinf(v)) return v > 0 ? "∞" : "−∞";
  if (v == std::floor(v) && std::abs(v) < 1e15) return fmt::format("{}", static_cast<long long>(v));
  return fmt::format("{:g}", v);
}

}  // namespace

std::string ParameterSpec::describeDefault() const {
  if (!defaultDescription.empty()) return defaultDescription;
  if (type == ParameterType::Flag) return "off";
  return defaultValue;
}

namespace {

/// "even", "a multiple of 3": what ParameterSpec::multipleOf asks, in words.
std::string multipleWords(int multipleOf) {
  return multipleOf == 2 ? "even" : "a multiple of " + std::to_string(multipleOf);
}

}  // namespace

std::string ParameterSpec::describeRange() const {
  switch (type) {
    case ParameterType::Flag:
      return "";
    case ParameterType::Choice:
      return joinNames(choices);
    case ParameterType::Integer:
    case ParameterType::Real:
      if (!choices.empty()) return "a number or " + joinNames(choices);
      {
        const std::string multiple = multipleOf > 1 ? ", " + multipleWords(multipleOf) : "";
        if (std::isinf(minimum) && std::isinf(maximum)) return multiple.empty() ? "" : multiple.substr(2);
        if (minimum == kPositive) return (std::isinf(maximum) ? "> 0" : "0 < x ≤ " + formatBound(maximum)) + multiple;
        if (std::isinf(maximum) || maximum >= 2147483647) return "≥ " + formatBound(minimum) + multiple;
        return formatBound(minimum) + "…" + formatBound(maximum) + multiple;
      }
  }
  return "";
}

void ParameterValues::set(const std::string &name, std::string text, InputLocation origin) {
  values_[name] = Given{std::move(text), std::move(origin)};
}

double parseParameter(const ParameterSpec &spec, const std::string &text, const InputLocation &origin) {
  switch (spec.type) {
    case ParameterType::Flag:
      if (text == "true" || text == "1" || text == "on") return 1;
      if (text == "false" || text == "0" || text == "off") return 0;
      throw InputError(origin, fmt::format("expected true or false, got '{}'", text));
    case ParameterType::Choice: {
      auto it = std::find(spec.choices.begin(), spec.choices.end(), text);
      if (it == spec.choices.end())
        throw InputError(origin, fmt::format("expected one of {}, got '{}'", joinNames(spec.choices), text));
      return double(it - spec.choices.begin());
    }
    case ParameterType::Integer:
    case ParameterType::Real: {
      if (std::find(spec.choices.begin(), spec.choices.end(), text) != spec.choices.end()) return NAN;  // a word
      // strtod is locale-dependent only in its decimal point; Radiant never sets a locale.
      errno = 0;
      char *end = nullptr;
      const double value = text.empty() ? NAN : std::strtod(text.c_str(), &end);
      const bool parsed = !text.empty() && end && *end == '\0' && errno != ERANGE && std::isfinite(value);
      const bool integral = spec.type == ParameterType::Real || (parsed && value == std::floor(value));
      if (!parsed || !integral) {
        std::string words;
        for (const std::string &w : spec.choices) words += " or '" + w + "'";
        throw InputError(origin,
                         fmt::format("expected {}{}, got '{}'",
                                     spec.type == ParameterType::Integer ? "an integer" : "a number", words, text));
      }
      if (value < spec.minimum || value > spec.maximum)
        throw InputError(origin, fmt::format("must be in {}, got {}", spec.describeRange(), text));
      if (spec.multipleOf > 1 && std::fmod(value, double(spec.multipleOf)) != 0)
        throw InputError(origin, fmt::format("must be {}, got {}", multipleWords(spec.multipleOf), text));
      return value;
    }
  }
  throw std::logic_error("unknown parameter type");
}

Parameters::Parameters(const ParameterTable &table, ParameterValues given) : table_(&table), given_(std::move(given)) {}

const ParameterSpec &Parameters::spec(const std::string &name) const {
  if (table_)
    for (const ParameterSpec &s : *table_)
      if (s.name == name) return s;
  throw std::logic_error("parameter '" + name + "' is not in the method's table");
}

std::string Parameters::text(const ParameterSpec &s) const {
  auto it = given_.all().find(s.name);
  return it != given_.all().end() ? it->second.text : s.defaultValue;
}

bool Parameters::given(const std::string &name) const {
  spec(name);
  return given_.has(name);
}

InputLocation Parameters::origin(const std::string &name) const {
  auto it = given_.all().find(name);
  return it != given_.all().end() ? it->second.origin : InputLocation::ofParameter(name);
}

bool Parameters::flag(const std::string &name) const {
  const ParameterSpec &s = spec(name);
  if (s.type != ParameterType::Flag) throw std::logic_error("parameter '" + name + "' is not a flag");
  return parseParameter(s, text(s), origin(name)) != 0;
}

long long Parameters::integer(const std::string &name) const {
  const ParameterSpec &s = spec(name);
  if (s.type != ParameterType::Integer) throw std::logic_error("parameter '" + name + "' is not an integer");
  return static_cast<long long>(parseParameter(s, text(s), origin(name)));
}

double Parameters::real(const std::string &name) const {
  const ParameterSpec &s = spec(name);
  if (s.type != ParameterType::Real && s.type != ParameterType::Integer)
    throw std::logic_error("parameter '" + name + "' is not a number");
  return parseParameter(s, text(s), origin(name));
}

std::string Parameters::choice(const std::string &name) const {
  const ParameterSpec &s = spec(name);
  if (s.type != ParameterType::Choice) throw std::logic_error("parameter '" + name + "' is not a choice");
  parseParameter(s, text(s), origin(name));
  return text(s);
}

void checkParameters(const ParameterTable &table, const ParameterValues &given, const std::string &owner,
                     const std::vector<std::pair<std::string, const ParameterTable *>> &others) {
  for (const auto &[name, value] : given.all()) {
    // By init-capture: clang before 16 (the fuzz build's clang 14) cannot capture a structured binding.
    auto declared =
        std::find_if(table.begin(), table.end(), [&name = name](const ParameterSpec &s) { return s.name == name; });
    if (declared != table.end()) {
      parseParameter(*declared, value.text, value.origin);
      if (!declared->excludes.empty() && given.has(declared->excludes))
        throw InputError(value.origin, fmt::format("give {} or {}, not both", declared->excludes, name));
      continue;
    }
    std::vector<std::string> users;
    std::vector<std::string> known;
    for (const auto &[otherName, otherTable] : others)
      for (const ParameterSpec &s : *otherTable) {
        if (s.name == name && std::find(users.begin(), users.end(), otherName) == users.end())
          users.push_back(otherName);
        known.push_back(s.name);
      }
    if (!users.empty())
      throw InputError(value.origin, fmt::format("{} does not use it (used by {})", owner, joinNames(users)));
    std::string best;
    for (const std::string &k : known) {
      const std::string candidate =
          best.empty() ? closestMatch(name, {k.c_str()}) : closestMatch(name, {best.c_str(), k.c_str()});
      if (!candidate.empty()) best = candidate;
    }
    throw InputError(value.origin, fmt::format("unknown parameter '{}'{}", name,
                                               best.empty() ? std::string() : " (did you mean '" + best + "'?)"));
  }
}

}  // namespace radiant
