#include "sweep_run.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>

#include "config/config.h"
#include "sweep/runner.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace lbtest {

fs::path runConfig(const json& cfg, const std::string& tag, const std::string& pathsDir) {
  const std::string dir = pathsDir.empty() ? std::string(LODBENCH_SOURCE_DIR) + "/configs" : pathsDir;
  lb::Config c = lb::parseConfig(cfg.dump(), tag + ".json", dir);
  const fs::path out = fs::path(::testing::TempDir()) / ("lodbench_" + tag + "_" + std::to_string(getpid()));
  fs::remove_all(out);
  lb::RunOptions o;
  o.outDir = out.string();
  o.progress = false;
  o.validation = std::getenv("LODBENCH_VALIDATION") != nullptr;
  const lb::RunTotals t = lb::runSweep(c, o);
  EXPECT_EQ(t.failed, 0) << tag;
  EXPECT_EQ(t.validationErrors, 0) << tag;
  return out;
}

std::vector<json> caseRecords(const fs::path& runDir) {
  std::vector<json> cases;
  for (const auto& e : fs::directory_iterator(runDir / "cases")) cases.push_back(json::parse(std::ifstream(e.path())));
  return cases;
}

std::vector<json> sweepCases(const json& cfg, const std::string& tag, const std::string& pathsDir) {
  const fs::path dir = runConfig(cfg, tag, pathsDir);
  std::vector<json> cases = caseRecords(dir);
  fs::remove_all(dir);
  return cases;
}

std::map<int, double> perFrame(const json& caseRecord, const std::string& key) {
  std::map<int, double> out;
  for (const json& f : caseRecord["frames"])
    if (f.contains(key) && f[key].is_number()) out[f["frame"].get<int>()] = f[key].get<double>();
  return out;
}

}  // namespace lbtest
