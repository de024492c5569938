#include "config/config_reader.h"

#include <filesystem>
#include <fstream>

#include "number_text.h"

namespace lb {

using nlohmann::json;

std::string resolvePath(const std::string& base, const std::string& p) {
  if (p.empty() || p[0] == '/' || base.empty()) return p;
  return base + "/" + p;
}

std::string inputFile(const ConfigReader& r, const json& v, const std::string& ptr, const std::string& base,
                      const char* what) {
  std::string path = resolvePath(base, r.string(v, ptr));
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    r.fail(ptr, "'" + printable(path, 200) + "' is a directory, not a " + what);
  if (!std::ifstream(path)) r.fail(ptr, "cannot open " + std::string(what) + " '" + printable(path, 200) + "'");
  return path;
}

}  // namespace lb
