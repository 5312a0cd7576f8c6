// Typed access to a parsed JSON document, with the JSON path of every value.
//
// The scene loader never touches nlohmann::json directly: it asks a JsonNode
// for "an array of 3 numbers or a number" at a key, and a wrong value becomes an
// InputError that names the file, the JSON path (RFC 6901 pointer, e.g.
// /materials/white/reflectance) and what was expected instead. Unknown keys are
// errors with a did-you-mean suggestion (a typo never silently does
// nothing); "comment" is accepted everywhere and ignored.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "util/error.h"
#include "util/math.h"
#include "util/spectrum.h"

namespace radiant {

using Json = nlohmann::ordered_json;

/// The deepest nesting of arrays and objects parseJsonText accepts.
constexpr int kMaxJsonDepth = 64;

/// Parses JSON text; a syntax error (or a number too large for a double, which
/// nlohmann reports separately) becomes an InputError with line and column.
Json parseJsonText(const std::string &text, const std::string &file);

/// The closest of `candidates` to `word` (radiant::closestMatch over a runtime list), or "".
std::string closestName(const std::string &word, const std::vector<std::string> &candidates);

/// "; did you mean 'x'?" or "" when nothing is close.
std::string didYouMean(const std::string &word, const std::vector<std::string> &candidates);

/// Escapes a key for use in a JSON pointer (RFC 6901: ~ → ~0, / → ~1).
std::string jsonPointerEscape(const std::string &key);

/// A JSON value plus where it came from.
class JsonNode {
 public:
  JsonNode(const Json &value, std::string file, std::string path)
      : value_(&value), file_(std::move(file)), path_(std::move(path)) {}

  const Json &value() const { return *value_; }
  const std::string &file() const { return file_; }
  const std::string &path() const { return path_.empty() ? rootPath() : path_; }
  InputLocation location() const { return {file_, 0, 0, path()}; }

  [[noreturn]] void fail(const std::string &message) const;

  bool isObject() const { return value_->is_object(); }
  bool has(const std::string &key) const { return value_->is_object() && value_->contains(key); }
  JsonNode child(const std::string &key) const;  ///< the member; fails if missing
  JsonNode element(size_t index) const;
  size_t size() const { return value_->size(); }

  /// Fails unless this is an object.
  void expectObject() const;
  /// Fails on a key not in `allowed` ("comment" is always allowed), with a suggestion.
  void checkKeys(const std::vector<std::string> &allowed) const;

  // Conversions of this value; each fails with "expected …, got …".
  double asNumber() const;  ///< finite
  int64_t asInteger(int64_t minimum, int64_t maximum) const;
  std::string asString() const;
  Vec3 asVec3() const;    ///< array of 3 finite numbers
  Bands asBands() const;  ///< array of 3 finite numbers, or one number for all bands
  std::vector<JsonNode> asArray(size_t minimumSize = 0, size_t maximumSize = SIZE_MAX) const;

  // Optional members: the default when the key is absent.
  double number(const std::string &key, double fallback) const;
  int64_t integer(const std::string &key, int64_t fallback, int64_t minimum, int64_t maximum) const;
  std::string string(const std::string &key, const std::string &fallback) const;
  Vec3 vec3(const std::string &key, const Vec3 &fallback) const;
  Bands bands(const std::string &key, const Bands &fallback) const;

 private:
  static const std::string &rootPath();
  const Json *value_;
  std::string file_;
  std::string path_;
};

/// "a string", "an array", "the number 3", … for "got …" in messages.
std::string describeJson(const Json &value);

}  // namespace radiant
