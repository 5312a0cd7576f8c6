#include "util/parse_number.h"

#include <cctype>
#include <charconv>
#include <cmath>

namespace radiant {

namespace {

/// Drops one leading '+' (std::from_chars takes '-' only); false when what
/// follows the sign cannot start a decimal number ("inf", "nan", "0x…" are
/// refused by the caller's digit check).
bool stripPlus(std::string_view &text) {
  if (!text.empty() && text.front() == '+') {
    text.remove_prefix(1);
    if (!text.empty() && text.front() == '-') return false;  // "+-1"
  }
  return !text.empty();
}

bool isDigit(char c) {
  return std::isdigit(static_cast<unsigned char>(c)) != 0;
}

}  // namespace

bool parseDecimal(std::string_view text, double &value) {
  if (!stripPlus(text)) return false;
  // Only digits, '.', a sign after the exponent and 'e'/'E' may appear: this
  // refuses "inf", "nan" and hexadecimal, which from_chars' general format
  // would read.
  size_t start = text.front() == '-' ? 1 : 0;
  if (start >= text.size() || !(isDigit(text[start]) || text[start] == '.')) return false;
  for (size_t i = start; i < text.size(); ++i) {
    const char c = text[i];
    if (!(isDigit(c) || c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-')) return false;
  }
  double parsed = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), parsed);
  if (end != text.data() + text.size()) return false;
  if (error == std::errc::result_out_of_range) {
    // Overflow is an error; underflow (1e-400) is zero, as every parser reads it.
    const size_t exponent = text.find_first_of("eE");
    if (exponent == std::string_view::npos || exponent + 1 >= text.size() || text[exponent + 1] != '-') return false;
    parsed = 0;
  } else if (error != std::errc()) {
    return false;
  }
  if (!std::isfinite(parsed)) return false;
  value = parsed;
  return true;
}

bool parseInteger(std::string_view text, int64_t &value) {
  if (!stripPlus(text)) return false;
  int64_t parsed = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), parsed);
  if (error != std::errc() || end != text.data() + text.size()) return false;
  value = parsed;
  return true;
}

}  // namespace radiant
