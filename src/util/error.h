// The one error path of Radiant: loaders and option parsers throw
// InputError with the location of the bad input; main() catches it once, prints
// it and exits non-zero.
#pragma once

#include <stdexcept>
#include <string>

namespace radiant {

/// Where a bad value came from: a file, and a line (OBJ/MTL, JSON text) or a
/// JSON path such as /materials/2/reflectance.
struct InputLocation {
  std::string file;
  int line = 0;    // 1-based; 0 when unknown
  int column = 0;  // 1-based; 0 when unknown
  std::string jsonPath;
  /// A method's or stage's parameter ("mesh-size"), when the value came from
  /// whatever set it: the library names the parameter, and the command line
  /// prints it as its flag (--mesh-size).
  std::string parameter;

  static InputLocation ofParameter(std::string name) {
    InputLocation where;
    where.parameter = std::move(name);
    return where;
  }
  std::string toString() const;
};

class InputError : public std::runtime_error {
 public:
  InputError(InputLocation where, const std::string &what);
  const InputLocation &location() const { return where_; }
  /// What is wrong, without the location.
  const std::string &message() const { return message_; }

 private:
  InputLocation where_;
  std::string message_;
};

/// The closest candidate to `word` by edit distance, or "" if none is close
/// enough to be a plausible typo. Used for "did you mean" in error messages.
std::string closestMatch(const std::string &word, const std::initializer_list<const char *> &candidates);

}  // namespace radiant
