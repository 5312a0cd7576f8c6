#include "util/error.h"

#include <algorithm>
#include <vector>

namespace radiant {

std::string InputLocation::toString() const {
  if (file.empty() && !parameter.empty()) return "parameter " + parameter;
  std::string s = file.empty() ? std::string("<input>") : file;
  if (line > 0) {
    s += ":" + std::to_string(line);
    if (column > 0) s += ":" + std::to_string(column);
  }
  if (!jsonPath.empty()) s += ": at " + jsonPath;
  return s;
}

InputError::InputError(InputLocation where, const std::string &what)
    : std::runtime_error(where.toString() + ": " + what), where_(std::move(where)), message_(what) {}

static size_t editDistance(const std::string &a, const std::string &b) {
  std::vector<size_t> previous(b.size() + 1), current(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) previous[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      size_t substitute = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitute});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

std::string closestMatch(const std::string &word, const std::initializer_list<const char *> &candidates) {
  std::string best;
  size_t bestDistance = std::max<size_t>(2, word.size() / 3) + 1;
  for (const char *c : candidates) {
    size_t d = editDistance(word, c);
    if (d < bestDistance) {
      bestDistance = d;
      best = c;
    }
  }
  return best;
}

}  // namespace radiant
