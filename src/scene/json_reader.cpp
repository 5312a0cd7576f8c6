#include "scene/json_reader.h"

#include <cmath>
#include <limits>

namespace radiant {

namespace {

/// nlohmann reports the 1-based index of the last byte it read; turn it into a
/// 1-based line and column (a column counts bytes, as editors do for ASCII).
InputLocation locationOfByte(const std::string &text, size_t byte, const std::string &file) {
  size_t position = byte == 0 ? 0 : std::min(byte - 1, text.size());
  int line = 1;
  size_t lineStart = 0;
  for (size_t i = 0; i < position; ++i)
    if (text[i] == '\n') {
      ++line;
      lineStart = i + 1;
    }
  return {file, line, static_cast<int>(position - lineStart) + 1, ""};
}

/// nlohmann's message without its own "[json.exception…] parse error at line…:" prefix.
std::string parseErrorReason(const std::string &what) {
  size_t column = what.find(", column ");
  if (column != std::string::npos) {
    size_t colon = what.find(": ", column);
    if (colon != std::string::npos) return what.substr(colon + 2);
  }
  size_t bracket = what.find("] ");
  return bracket == std::string::npos ? what : what.substr(bracket + 2);
}

/// The first place where arrays and objects nest deeper than `limit`, or
/// std::string::npos. nlohmann's parser keeps its own stack, but a document
/// nested 10⁵ deep still overflows the call stack where it is copied, printed
/// or destroyed recursively; no scene needs more than a handful of levels.
size_t tooDeep(const std::string &text, int limit) {
  int depth = 0;
  bool inString = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > limit) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::string::npos;
}

}  // namespace

Json parseJsonText(const std::string &text, const std::string &file) {
  if (size_t at = tooDeep(text, kMaxJsonDepth); at != std::string::npos)
    throw InputError(locationOfByte(text, at + 1, file), "arrays and objects nest more than " +
                                                             std::to_string(kMaxJsonDepth) +
                                                             " levels deep here; a Radiant scene needs a few");
  try {
    return Json::parse(text);
  } catch (const nlohmann::json::parse_error &e) {
    throw InputError(locationOfByte(text, e.byte, file), "invalid JSON: " + parseErrorReason(e.what()));
  } catch (const nlohmann::json::out_of_range &e) {
    // Error 406: a number such as 1e999 overflows to infinity. nlohmann gives no
    // position, so find the literal it quotes in the text.
    std::string what = e.what();
    size_t open = what.find('\''), close = what.rfind('\'');
    InputLocation where{file, 0, 0, ""};
    std::string literal;
    if (open != std::string::npos && close > open) {
      literal = what.substr(open + 1, close - open - 1);
      size_t at = text.find(literal);
      if (at != std::string::npos) where = locationOfByte(text, at + 1, file);
    }
    throw InputError(where, "the number " + literal + " is too large for a double (it would be infinite)");
  }
}

std::string closestName(const std::string &word, const std::vector<std::string> &candidates) {
  // closestMatch takes a fixed list; comparing the best so far with each new
  // candidate keeps its threshold and tie-breaking (the first listed wins).
  std::string best;
  for (const std::string &candidate : candidates) {
    if (best.empty())
      best = closestMatch(word, {candidate.c_str()});
    else
      best = closestMatch(word, {best.c_str(), candidate.c_str()});
  }
  return best;
}

std::string didYouMean(const std::string &word, const std::vector<std::string> &candidates) {
  std::string best = closestName(word, candidates);
  return best.empty() ? std::string() : "; did you mean '" + best + "'?";
}

std::string jsonPointerEscape(const std::string &key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

std::string describeJson(const Json &value) {
  switch (value.type()) {
    case Json::value_t::null:
      return "null";
    case Json::value_t::object:
      return "an object";
    case Json::value_t::array:
      return "an array of " + std::to_string(value.size());
    case Json::value_t::string:
      return "a string";
    case Json::value_t::boolean:
      return value.get<bool>() ? "true" : "false";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float:
      return "the number " + value.dump();
    default:
      return "an unsupported value";
  }
}

const std::string &JsonNode::rootPath() {
  static const std::string root = "/";
  return root;
}

void JsonNode::fail(const std::string &message) const {
  throw InputError(location(), message);
}

JsonNode JsonNode::child(const std::string &key) const {
  expectObject();
  auto it = value_->find(key);
  if (it == value_->end()) fail("missing required key '" + key + "'");
  return JsonNode(*it, file_, path_ + "/" + jsonPointerEscape(key));
}

JsonNode JsonNode::element(size_t index) const {
  return JsonNode((*value_)[index], file_, path_ + "/" + std::to_string(index));
}

void JsonNode::expectObject() const {
  if (!value_->is_object()) fail("expected an object, got " + describeJson(*value_));
}

void JsonNode::checkKeys(const std::vector<std::string> &allowed) const {
  expectObject();
  for (auto it = value_->begin(); it != value_->end(); ++it) {
    const std::string &key = it.key();
    if (key == "comment") continue;
    bool known = false;
    for (const std::string &a : allowed) known = known || a == key;
    if (!known) {
      JsonNode(it.value(), file_, path_ + "/" + jsonPointerEscape(key))
          .fail("unknown key '" + key + "'" + didYouMean(key, allowed));
    }
  }
}

double JsonNode::asNumber() const {
  if (!value_->is_number()) fail("expected a number, got " + describeJson(*value_));
  double x = value_->get<double>();
  if (!std::isfinite(x)) fail("expected a finite number");
  return x;
}

int64_t JsonNode::asInteger(int64_t minimum, int64_t maximum) const {
  if (!value_->is_number()) fail("expected an integer, got " + describeJson(*value_));
  double x = value_->get<double>();
  if (!std::isfinite(x) || x != std::floor(x)) fail("expected an integer, got " + describeJson(*value_));
  // Compare as doubles first so huge values cannot overflow the cast.
  if (x < static_cast<double>(minimum) || x > static_cast<double>(maximum))
    fail("expected an integer in [" + std::to_string(minimum) + ", " + std::to_string(maximum) + "], got " +
         value_->dump());
  int64_t i =
      value_->is_number_unsigned()
          ? static_cast<int64_t>(std::min<uint64_t>(value_->get<uint64_t>(), std::numeric_limits<int64_t>::max()))
          : static_cast<int64_t>(x);
  if (i < minimum || i > maximum)
    fail("expected an integer in [" + std::to_string(minimum) + ", " + std::to_string(maximum) + "], got " +
         value_->dump());
  return i;
}

std::string JsonNode::asString() const {
  if (!value_->is_string()) fail("expected a string, got " + describeJson(*value_));
  return value_->get<std::string>();
}

Vec3 JsonNode::asVec3() const {
  if (!value_->is_array() || value_->size() != 3) fail("expected an array of 3 numbers, got " + describeJson(*value_));
  Vec3 v;
  for (int i = 0; i < 3; ++i) v[i] = element(static_cast<size_t>(i)).asNumber();
  return v;
}

Bands JsonNode::asBands() const {
  if (value_->is_number()) return Bands(asNumber());
  if (!value_->is_array() || value_->size() != kBandCount)
    fail("expected an array of " + std::to_string(kBandCount) + " numbers or a number, got " + describeJson(*value_));
  Bands b;
  for (int i = 0; i < kBandCount; ++i) b[i] = element(static_cast<size_t>(i)).asNumber();
  return b;
}

std::vector<JsonNode> JsonNode::asArray(size_t minimumSize, size_t maximumSize) const {
  if (!value_->is_array()) fail("expected an array, got " + describeJson(*value_));
  if (value_->size() < minimumSize || value_->size() > maximumSize) {
    std::string expected = minimumSize == maximumSize ? std::to_string(minimumSize)
                           : maximumSize == SIZE_MAX
                               ? "at least " + std::to_string(minimumSize)
                               : std::to_string(minimumSize) + " to " + std::to_string(maximumSize);
    fail("expected an array of " + expected + " elements, got " + describeJson(*value_));
  }
  std::vector<JsonNode> out;
  for (size_t i = 0; i < value_->size(); ++i) out.push_back(element(i));
  return out;
}

double JsonNode::number(const std::string &key, double fallback) const {
  return has(key) ? child(key).asNumber() : fallback;
}

int64_t JsonNode::integer(const std::string &key, int64_t fallback, int64_t minimum, int64_t maximum) const {
  return has(key) ? child(key).asInteger(minimum, maximum) : fallback;
}

std::string JsonNode::string(const std::string &key, const std::string &fallback) const {
  return has(key) ? child(key).asString() : fallback;
}

Vec3 JsonNode::vec3(const std::string &key, const Vec3 &fallback) const {
  return has(key) ? child(key).asVec3() : fallback;
}

Bands JsonNode::bands(const std::string &key, const Bands &fallback) const {
  return has(key) ? child(key).asBands() : fallback;
}

}  // namespace radiant
