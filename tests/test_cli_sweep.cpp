// What the command line says about a sweep before and around it: --dry-run's count,
// time and disk estimates; "did you mean" for mistyped schemes, parameters and fields; devices
// naming CPU rasterizers; compare saying "no timing verdict" once, not once per case.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.h"
#include "did_you_mean.h"

namespace {

namespace fs = std::filesystem;
using lb::test::CliOut;

const std::string kSrc = LODBENCH_SOURCE_DIR;

fs::path fresh(const std::string& name) {
  fs::path d = fs::path(::testing::TempDir()) / "lodbench_cli_sweep" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// lodbench from `dir`, validation as ctest sets it.
CliOut in(const fs::path& dir, const std::string& args) {
  return lb::test::shell("cd '" + dir.string() + "' && " + LODBENCH_BINARY + " " + args);
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

void writeConfig(const fs::path& file, const std::string& schemes, const std::string& extra = "") {
  std::ofstream(file) << R"({"name": "dry", "resolution": [48, 32], "grid": 4, "fps": 10, "warmup_frames": 0,
    "max_frames": 3, "terrain": {"type": "procedural", "size": 33, "seed": 5}, )"
                      << extra << R"("paths": [")" << kSrc << R"(/configs/paths/flyover.csv"], "schemes": [)" << schemes
                      << "]}";
}

}  // namespace

TEST(CliSweep, DryRunCountsAndEstimatesFromAnEarlierRunOfItsFolder) {
  fs::path d = fresh("dry");
  writeConfig(d / "dry.json", R"({"name": "uniform", "params": {"level": 3}}, "sphere")");
  CliOut o = in(d, "run dry.json --dry-run");
  ASSERT_EQ(o.code, 0) << o.text;
  EXPECT_NE(o.text.find("lodbench: 2 cases\n"), std::string::npos) << o.text;
  EXPECT_NE(o.text.find("estimated time: no estimate (no earlier run of 'dry'"), std::string::npos) << o.text;
  // 2 cases x 3 frames, no images; bytes per record the CI baseline's without an earlier run.
  EXPECT_NE(o.text.find("estimated disk: about 10.2 kB of records and summaries (6 frame records at about 1.7 kB each"),
            std::string::npos)
      << o.text;
  EXPECT_FALSE(fs::exists(d / "results")) << "a dry run writes nothing";

  o = in(d, "run dry.json --out results/dry/first -q");
  ASSERT_EQ(o.code, 0) << o.text;
  o = in(d, "run dry.json --dry-run");
  ASSERT_EQ(o.code, 0) << o.text;
  EXPECT_NE(o.text.find("estimated time: about "), std::string::npos) << o.text;
  EXPECT_NE(o.text.find("from the costs of results/dry/first"), std::string::npos) << o.text;
  EXPECT_NE(o.text.find("(6 frame records at the bytes per record of results/dry/first)"), std::string::npos) << o.text;

  // Against the finished folder: everything kept, nothing to run. With a scheme more: one to run.
  writeConfig(d / "dry.json", R"({"name": "uniform", "params": {"level": 3}}, "sphere", "distance")");
  o = in(d, "run dry.json --dry-run --out results/dry/first");
  ASSERT_EQ(o.code, 0) << o.text;
  EXPECT_NE(o.text.find("results/dry/first exists: 2 finished case(s) kept, 0 changed (refused without "
                        "--rerun-changed), 0 stale, 1 to run"),
            std::string::npos)
      << o.text;
  EXPECT_NE(o.text.find("(3 frame records at"), std::string::npos) << "only the new case's records: " << o.text;
}

TEST(CliSweep, MistypedNamesGetTheNearestKnownOne) {
  EXPECT_EQ(lb::editDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(lb::editDistance("Sphere", "sphere"), 0u);
  EXPECT_EQ(lb::didYouMean("sphre", {"uniform", "sphere", "sphere-edge"}), "; did you mean 'sphere'?");
  EXPECT_EQ(lb::didYouMean("zzzzzz", {"uniform", "sphere"}), "") << "nothing close: no guess";

  fs::path d = fresh("typos");
  struct Typo {
    std::string schemes, extra, expect;
  };
  for (const Typo& t : {Typo{R"("sphre")", "", "unknown scheme 'sphre' (known: "},
                        Typo{R"({"name": "sphere", "params": {"tri-size": 3}})", "", "has no parameter 'tri-size'"},
                        Typo{R"("sphere")", R"("resolutoin": [64, 48], )", "unknown key (allowed: "}}) {
    writeConfig(d / "typo.json", t.schemes, t.extra);
    CliOut o = in(d, "run typo.json --dry-run");
    EXPECT_EQ(o.code, 2) << o.text;
    EXPECT_NE(o.text.find(t.expect), std::string::npos) << o.text;
    EXPECT_EQ(count(o.text, "did you mean '"), 1u) << o.text;
  }
  writeConfig(d / "typo.json", R"("sphre")");
  EXPECT_NE(in(d, "run typo.json --dry-run").text.find("did you mean 'sphere'?"), std::string::npos);
  writeConfig(d / "typo.json", R"({"name": "sphere", "params": {"tri-size": 3}})");
  EXPECT_NE(in(d, "run typo.json --dry-run").text.find("did you mean 'tri_size'?"), std::string::npos);
  writeConfig(d / "typo.json", R"("sphere")", R"("resolutoin": [64, 48], )");
  EXPECT_NE(in(d, "run typo.json --dry-run").text.find("did you mean 'resolution'?"), std::string::npos);

  CliOut o = in(d, "render --scheme sphre --path " + kSrc + "/configs/paths/flyover.csv --out x.png");
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find("--scheme: unknown scheme 'sphre' (known: "), std::string::npos) << o.text;
  EXPECT_NE(o.text.find("did you mean 'sphere'?"), std::string::npos) << o.text;
  o = in(d, "rn typo.json");
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find("did you mean 'run'?"), std::string::npos) << o.text;
}

// The test device is lavapipe, a VK_PHYSICAL_DEVICE_TYPE_CPU device: devices must say so under it.
TEST(CliSweep, DevicesSaysWhichDeviceIsACpuRasterizer) {
  CliOut o = lb::test::lodbench("devices", false);
  ASSERT_EQ(o.code, 0) << o.text;
  const size_t llvmpipe = o.text.find("llvmpipe");
  ASSERT_NE(llvmpipe, std::string::npos) << o.text;
  const size_t note = o.text.find("CPU software rasterizer (VK_PHYSICAL_DEVICE_TYPE_CPU)", llvmpipe);
  ASSERT_NE(note, std::string::npos) << o.text;
  EXPECT_LT(note, o.text.find("largest terrain", llvmpipe)) << "the note belongs to the llvmpipe entry";
}

// One run against one run gives no timing verdict; the reason is said once, not once per case.
TEST(CliSweep, CompareSaysNoTimingVerdictOnce) {
  const std::string r1 = kSrc + "/results/baseline/ci/r1";
  // Stdout only (the Markdown); stderr repeats the NOT CHECKED lines for a terminal.
  CliOut o = lb::test::shell("(" + std::string(LODBENCH_BINARY) + " compare " + r1 + " " + r1 + " 2>/dev/null)");
  ASSERT_EQ(o.code, 0) << o.text;
  EXPECT_EQ(count(o.text, "no timing verdict: 1 baseline and 1 candidate round(s)"), 1u) << o.text;
  const size_t from = o.text.find("## GPU time"), to = o.text.find("\n## ", from + 1);
  ASSERT_NE(from, std::string::npos) << o.text;
  const std::string table = o.text.substr(from, to - from);
  const size_t rows = count(table, "\n| `");
  EXPECT_GT(rows, 1u) << table;
  EXPECT_EQ(count(table, "no verdict (the reason above)"), rows) << "every timing row points to the one reason\n"
                                                                 << table;
}
