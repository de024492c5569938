// The report tests' fixture run (tests/data/report_run) and small file helpers, shared by
// test_report.cpp and test_report_page.cpp.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "report/report.h"

namespace lb::test {

inline const std::filesystem::path kFixture = std::filesystem::path(LODBENCH_SOURCE_DIR) / "tests/data/report_run";

inline nlohmann::json readJson(const std::filesystem::path& p) {
  std::ifstream f(p);
  return nlohmann::json::parse(f);
}

inline std::string readText(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// A writable copy of the fixture, so the report goes to its default place <run>/report.
inline std::filesystem::path copyFixture(const std::string& name) {
  std::filesystem::path d = std::filesystem::path(::testing::TempDir()) / name;
  std::filesystem::remove_all(d);
  std::filesystem::copy(kFixture, d, std::filesystem::copy_options::recursive);
  return d;
}

inline ReportOutput writeNoHtml(const std::filesystem::path& run) {
  ReportOptions o;
  o.runDir = run.string();
  o.html = false;
  return writeReport(o);
}

}  // namespace lb::test
