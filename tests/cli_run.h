#pragma once
// Running the lodbench binary from tests: exit code and combined output.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace lb::test {

struct CliOut {
  int code = -1;
  std::string text;
};

// A shell command line: exit code and combined output.
inline CliOut shell(const std::string& cmd) {
  CliOut o;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), int(buf.size()), p)) o.text += buf.data();
  int status = pclose(p);
  o.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return o;
}

// timing = true leaves the validation layer off (ctest turns it on for everything): its CPU work
// competes with lavapipe's threads and would blur the figures.
inline CliOut lodbench(const std::string& args, bool timing = true) {
  return shell(std::string(timing ? "env -u LODBENCH_VALIDATION " : "") + LODBENCH_BINARY + " " + args);
}

inline const std::string kTinyConfig = std::string(LODBENCH_SOURCE_DIR) + "/tests/configs/tiny.json";

inline std::string freshDir(const std::string& name) {
  std::string d = ::testing::TempDir() + "/lodbench_ab/" + name;
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(std::filesystem::path(d).parent_path());
  return d;
}

inline nlohmann::json readJson(const std::string& file) {
  return nlohmann::json::parse(std::ifstream(file));
}

}  // namespace lb::test
