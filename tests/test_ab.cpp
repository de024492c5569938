// On lavapipe through the CLI: the planted slowdown's draws are valid Vulkan, and compare catches
// one changed counter in a copy of a real run. (The A/B timing tests are in tests/timing/.)
#include <gtest/gtest.h>

#include "cli_run.h"

namespace lb::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

TEST(Ab, PlantedSlowdownIsValidationClean) {
  std::string out = freshDir("slow_validated");
  CliOut o = lodbench("run " + kTinyConfig + " --out " + out + " --quiet --validation --test-slowdown 0.2", false);
  EXPECT_EQ(o.code, 0) << o.text;
  json run = readJson(out + "/run.json");
  EXPECT_EQ(run["validation_errors"], 0);
  EXPECT_EQ(run["test_slowdown"], 0.2);  // recorded, so no one mistakes the run for data
}

// One frame's clip_invocations changed in a copy of a real run: caught exactly, naming case, frame, field.
TEST(Ab, PlantedCounterChangeIsCaughtExactly) {
  std::string base = freshDir("counter_base"), copy = freshDir("counter_copy");
  CliOut o = lodbench("run " + kTinyConfig + " --out " + base + " --quiet");
  ASSERT_EQ(o.code, 0) << o.text;
  EXPECT_EQ(lodbench("compare " + base + " " + base).code, 0);
  fs::copy(base, copy, fs::copy_options::recursive);
  std::string id = "sphere-tri_size3_proc65s1_flyover_64x48", file = copy + "/cases/" + id + ".json";
  json c = readJson(file);
  json& frame = c["frames"][12];
  ASSERT_EQ(frame["frame"], 12);
  uint64_t before = frame["clip_invocations"].get<uint64_t>();
  frame["clip_invocations"] = before + 1;
  std::ofstream(file) << c.dump(1);

  o = lodbench("compare " + base + " " + copy);
  EXPECT_EQ(o.code, 1) << o.text;
  std::string row = "| `" + id + "` | 12 | clip_invocations | " + std::to_string(before) + " | " +
                    std::to_string(before + 1) + " | 1 | clip_invocations |";
  EXPECT_NE(o.text.find(row), std::string::npos) << o.text;
  EXPECT_NE(o.text.find("REGRESSION in 1 of 2 cases"), std::string::npos) << o.text;
}

}  // namespace
}  // namespace lb::test
