// An MGF file split into entities (Ward et al., "The Materials and Geometry
// Format", LBNL 1995, section 2): one per line, a line ending in `\`
// continuing on the next, `#` starting a comment entity that is dropped.

#include <sstream>

#include "scene/mgf_detail.h"
#include "util/input_file.h"

namespace radiant::detail {

std::vector<MgfEntity> readMgfEntities(const std::string &path, const InputLocation &fileFrom) {
  constexpr size_t kMaxFileBytes = size_t(1) << 30;
  std::istringstream in(readInputFile(path, fileFrom, "MGF file", kMaxFileBytes));
  std::vector<MgfEntity> entities;
  std::string line;
  int lineNumber = 0;
  MgfEntity current;
  while (std::getline(in, line)) {
    ++lineNumber;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (current.words.empty()) current.line = lineNumber;
    bool continues = !line.empty() && line.back() == '\\';
    if (continues) line.pop_back();
    std::istringstream words(line);
    std::string word;
    while (words >> word) {
      if (current.words.empty() && word[0] == '#') break;  // a comment entity: the rest of the line
      current.words.push_back(word);
      if (current.words.size() > kMaxMgfEntityWords)
        throw InputError({path, current.line, 0, ""}, "an entity of more than 65536 words");
    }
    if (continues && !current.words.empty()) continue;
    if (!current.words.empty()) entities.push_back(std::move(current));
    current = MgfEntity{};
  }
  if (!current.words.empty()) entities.push_back(std::move(current));
  return entities;
}

}  // namespace radiant::detail
