#pragma once
// Numbers in messages and listings: the shortest text that reads back as the same
// double, plain where that is readable (0.5, 1000000, 0.0001) and in exponent form only for very
// large or small magnitudes, so "0 is outside [0.5, 64]" never reads "0.000000" and a range never
// reads "1e+06".
#include <charconv>
#include <cmath>
#include <string>

namespace lb {

inline std::string numberText(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  const double a = std::fabs(v);
  const bool plain = a == 0 || (a >= 1e-4 && a < 1e15);
  auto r = plain ? std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed)
                 : std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

}  // namespace lb
