#include "parameter_flags.h"

#include <fmt/format.h>

#include <algorithm>

namespace radiant {

namespace {

const char *typeName(const ParameterSpec &spec) {
  switch (spec.type) {
    case ParameterType::Integer:
      return "INT";
    case ParameterType::Real:
      return "NUMBER";
    case ParameterType::Choice:
      return "CHOICE";
    case ParameterType::Flag:
      return "";
  }
  return "";
}

}  // namespace

std::string groupOwner(const std::string &title) {
  const size_t space = title.rfind(' ');
  return space == std::string::npos ? title : title.substr(space + 1);
}

void ParameterFlags::add(CLI::App &app, const std::vector<ParameterGroup> &groups) {
  for (const ParameterGroup &group : groups) {
    CLI::Option_group *options = nullptr;
    for (const ParameterSpec &spec : *group.table) {
      if (flags_.count(spec.name)) continue;
      std::vector<std::string> alsoUsedBy;
      for (const ParameterGroup &other : groups)
        if (&other != &group && other.title != group.title)
          for (const ParameterSpec &s : *other.table)
            if (s.name == spec.name) alsoUsedBy.push_back(groupOwner(other.title));
      std::string help = spec.documentation;
      if (!spec.describeRange().empty() && spec.type != ParameterType::Choice)
        help += fmt::format(" ({})", spec.describeRange());
      // A parameter every group declares (the solvers' common ones) needs no list.
      if (!alsoUsedBy.empty() && alsoUsedBy.size() + 1 < groups.size()) {
        std::string also;
        for (const std::string &name : alsoUsedBy) also += (also.empty() ? "" : ", ") + name;
        help += fmt::format(" [also: {}]", also);
      }
      if (!options) options = app.add_option_group(group.title);
      Flag &flag = flags_[spec.name];
      flag.isFlag = spec.type == ParameterType::Flag;
      if (flag.isFlag) {
        flag.option = options->add_flag("--" + spec.name, flag.on, help);
      } else {
        flag.option = options->add_option("--" + spec.name, flag.text, help)->type_name(typeName(spec));
        if (!spec.describeDefault().empty()) flag.option->default_str(spec.describeDefault());
        if (spec.type == ParameterType::Choice) flag.option->type_name("{" + spec.describeRange() + "}");
      }
    }
  }
}

ParameterValues ParameterFlags::given() const {
  ParameterValues values;
  for (const auto &[name, flag] : flags_)
    if (flag.option->count() > 0) values.set(name, flag.isFlag ? "true" : flag.text, InputLocation{"--" + name});
  return values;
}

CLI::Validator seedRange() {
  return CLI::Validator(
      [](std::string &text) -> std::string {
        const bool digits = !text.empty() && text.size() <= 20 &&
                            std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
        // 2⁶⁴ − 1 has 20 digits: compare as strings of equal length.
        if (!digits || (text.size() == 20 && text > "18446744073709551615"))
          return "expected an integer from 0 to 18446744073709551615, got '" + text + "'";
        return "";
      },
      "SEED");
}

}  // namespace radiant
