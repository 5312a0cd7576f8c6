// Numbers in text files, read the same way everywhere and whatever the C
// locale: strtod would take "0x1p-2", "inf", "nan" and, under a German locale,
// "1,5", none of which the OBJ/MTL or Radiant's own formats allow.
#pragma once

#include <cstdint>
#include <string_view>

namespace radiant {

/// A decimal number as the text formats write it: an optional sign, digits
/// with an optional '.', an optional exponent ("-1.5e3", "+2", ".5", "7.").
/// False for anything else: surrounding text, hexadecimal, "inf", "nan", or a
/// value beyond a double's range (1e999).
bool parseDecimal(std::string_view text, double &value);

/// A decimal integer with an optional sign; false for anything else or for a
/// value outside int64_t.
bool parseInteger(std::string_view text, int64_t &value);

}  // namespace radiant
