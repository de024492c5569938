#pragma once
// A plugin's scheme next to its built-in twin (tests/test_plugins.cpp, test_plugin_install.cpp):
// the config, and the check that every frame measured the same.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "cli_run.h"

namespace lb::test {

// A plugin's scheme next to its built-in twin: every measured frame, few and small.
inline nlohmann::json twinConfig(const std::string& plugin) {
  return {{"name", "twin"},
          {"resolution", {64, 36}},
          {"grid", 4},
          {"fps", 30},
          {"warmup_frames", 1},
          {"max_frames", 3},
          {"terrain", {{"type", "procedural"}, {"size", 65}, {"seed", 1}, {"extent", 1000}, {"height_scale", 120}}},
          {"paths", {std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/flyover.csv"}},
          {"plugins", {plugin}},
          {"schemes", {"sphere", "own-sphere"}},
          {"measure", {{"every", 1}, {"passes", {"histogram", "error", "cracks", "popping"}}}},
          {"images", {{"frames", nlohmann::json::array()}, {"modes", nlohmann::json::array()}}}};
}

inline std::string writeConfig(const std::string& dir, const nlohmann::json& config) {
  std::filesystem::create_directories(dir);
  const std::string file = dir + "/config.json";
  std::ofstream(file) << config.dump(1);
  return file;
}

// Every value of every frame but the timings: counters, histograms, errors, cracks, popping.
inline void expectSameFrames(const std::string& run, const std::string& a, const std::string& b) {
  const nlohmann::json ja = lb::test::readJson(run + "/cases/" + a + "_proc65s1_flyover_64x36.json");
  const nlohmann::json jb = lb::test::readJson(run + "/cases/" + b + "_proc65s1_flyover_64x36.json");
  ASSERT_EQ(ja["status"], "ok") << ja["reason"];
  ASSERT_EQ(jb["status"], "ok") << jb["reason"];
  ASSERT_EQ(ja["frames"].size(), jb["frames"].size());
  const std::set<std::string> timing = {"gpu_ms", "cpu_ms", "cpu_harness_ms", "fps"};
  int compared = 0;
  for (size_t i = 0; i < ja["frames"].size(); ++i)
    for (auto& [k, v] : ja["frames"][i].items()) {
      if (timing.count(k)) continue;
      EXPECT_EQ(v, jb["frames"][i].value(k, nlohmann::json())) << "frame " << i << " " << k;
      ++compared;
    }
  EXPECT_GT(compared, 60);
  EXPECT_TRUE(ja["frames"][0].contains("hist") && ja["frames"][0].contains("err_p95_px"));
}

}  // namespace lb::test
