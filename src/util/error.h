// The one error path of Radiant (STYLE.md §12): loaders and option parsers throw
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

  std::string toString() const;
};

class InputError : public std::runtime_error {
 public:
  InputError(InputLocation where, const std::string &what);
  const InputLocation &location() const { return where_; }

 private:
  InputLocation where_;
};

/// The closest candidate to `word` by edit distance, or "" if none is close
/// enough to be a plausible typo. Used for "did you mean" in error messages.
std::string closestMatch(const std::string &word, const std::initializer_list<const char *> &candidates);

}  // namespace radiant
