#pragma once
#include <cstdio>
#include <stdexcept>
#include <string>

namespace lb {
// Bad user input (config, CSV, heightmap, flags). The message names file, line and field.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
// The device lacks a feature a case needs: the case is recorded as skipped, with this reason.
struct FeatureMissing : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Untrusted text quoted in a message: control and non-ASCII bytes as \xNN, cut after maxLen bytes,
// so a binary file named by mistake cannot write raw bytes to the terminal.
inline std::string printable(const std::string& s, size_t maxLen = 40) {
  std::string out;
  for (size_t i = 0; i < s.size() && i < maxLen; ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c < 0x7f && c != '\\') {
      out += char(c);
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    }
  }
  if (s.size() > maxLen) out += "...(" + std::to_string(s.size()) + " bytes)";
  return out;
}
}  // namespace lb
