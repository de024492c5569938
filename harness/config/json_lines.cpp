#include "config/json_lines.h"

#include <cctype>
#include <cstring>
#include <vector>

namespace lb {
namespace {

struct Scanner {
  const std::string& s;
  size_t i = 0;
  int line = 1;
  std::map<std::string, int> out;

  void ws() {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) {
      if (s[i] == '\n') ++line;
      ++i;
    }
  }
  std::string str() {  // at '"'
    std::string v;
    ++i;
    while (i < s.size() && s[i] != '"') {
      if (s[i] == '\\' && i + 1 < s.size()) ++i;
      v += s[i++];
    }
    ++i;
    return v;
  }
  static std::string escape(const std::string& key) {  // RFC 6901
    std::string e;
    for (char c : key) e += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
    return e;
  }
  void value(const std::string& ptr) {
    ws();
    out[ptr.empty() ? "" : ptr] = line;
    if (i >= s.size()) return;
    if (s[i] == '{') {
      ++i;
      ws();
      while (i < s.size() && s[i] != '}') {
        ws();
        std::string key = str();
        ws();
        ++i;  // ':'
        value(ptr + "/" + escape(key));
        ws();
        if (i < s.size() && s[i] == ',') ++i;
        ws();
      }
      ++i;
    } else if (s[i] == '[') {
      ++i;
      ws();
      for (int k = 0; i < s.size() && s[i] != ']'; ++k) {
        value(ptr + "/" + std::to_string(k));
        ws();
        if (i < s.size() && s[i] == ',') ++i;
        ws();
      }
      ++i;
    } else if (s[i] == '"') {
      str();
    } else {
      while (i < s.size() && !std::strchr(",]} \t\r\n", s[i])) ++i;
    }
  }
};

}  // namespace

std::map<std::string, int> jsonLineMap(const std::string& text) {
  Scanner sc{text};
  sc.value("");
  return sc.out;
}

}  // namespace lb
