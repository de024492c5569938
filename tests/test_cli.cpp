// The lodbench binary: --help everywhere, exit codes, and errors that name the bad input.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_run.h"

namespace {

using Out = lb::test::CliOut;

// Keeps the validation layer as ctest sets it.
Out runCli(const std::string& args) {
  return lb::test::lodbench(args, false);
}

const std::string kSrc = LODBENCH_SOURCE_DIR;

}  // namespace

TEST(Cli, HelpOnEverySubcommand) {
  for (const char* sub : {"", "list", "devices", "run", "render", "report"}) {
    Out o = runCli(std::string(sub) + " --help");
    EXPECT_EQ(o.code, 0) << sub << ": " << o.text;
    EXPECT_NE(o.text.find("Usage"), std::string::npos) << sub;
  }
}

TEST(Cli, ListShowsSchemesWithParameters) {
  Out o = runCli("list");
  EXPECT_EQ(o.code, 0);
  EXPECT_NE(o.text.find("sphere"), std::string::npos);
  EXPECT_NE(o.text.find("range [1, 64]"), std::string::npos) << o.text;
  // Columns sized from the content (long names broke them) and plain range numbers.
  EXPECT_NE(o.text.find("range [0, 10000]"), std::string::npos) << "not 1e+04: " << o.text;
  EXPECT_EQ(o.text.find("e+"), std::string::npos) << o.text;
  size_t defaultCol = std::string::npos, rangeCol = std::string::npos, descCol = std::string::npos;
  int paramLines = 0, triSize3 = 0;
  std::istringstream lines(o.text);
  for (std::string line; std::getline(lines, line);) {
    size_t d = line.find("  default "), r = line.find("  range [");
    if (d == std::string::npos) {
      if (line.empty() || line[0] == ' ') continue;
      size_t gap = line.find("  "), text = line.find_first_not_of(' ', gap);  // name, then the description
      if (descCol == std::string::npos) descCol = text;
      EXPECT_EQ(text, descCol) << "description column: " << line;
      continue;
    }
    ++paramLines;
    if (defaultCol == std::string::npos) defaultCol = d, rangeCol = r;
    EXPECT_EQ(d, defaultCol) << "default column: " << line;
    EXPECT_EQ(r, rangeCol) << "range column: " << line;
    triSize3 += line.find(" tri_size ") != std::string::npos && line.find("default 3 ") != std::string::npos;
  }
  EXPECT_GT(paramLines, 10);
  EXPECT_GE(triSize3, 3) << "sphere, sphere-edge, sphere-rings: tri_size default 3";
}

// Numbers in errors are the shortest round-trip text (std::to_string gave "0.000100" and
// CLI11's ranges "0.000000 to 0.500000"); --dry-run says nothing of shards when none was asked.
TEST(Cli, NumbersInErrorsAndDryRunWording) {
  std::string bad = ::testing::TempDir() + "/tiny_param.json";
  std::ofstream(bad) << "{\"name\": \"x\", \"paths\": [\"" << kSrc << "/configs/paths/flyover.csv\"],\n"
                     << " \"schemes\": [{\"name\": \"sphere\", \"params\": {\"tri_size\": 0.0001}}]}\n";
  Out o = runCli("run " + bad + " --dry-run");
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find("0.0001 is outside [0.5, 64]"), std::string::npos) << o.text;
  EXPECT_EQ(o.text.find("0.000"), o.text.find("0.0001")) << "no fixed 6-digit numbers: " << o.text;

  o = runCli("compare /nonexistent/a /nonexistent/b --alpha 0.9");
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find("0.9 is outside [1e-09, 0.5]"), std::string::npos) << o.text;
  EXPECT_EQ(o.text.find("0.000000"), std::string::npos) << o.text;

  o = runCli("run " + lb::test::kTinyConfig + " --dry-run");
  EXPECT_EQ(o.code, 0) << o.text;
  EXPECT_NE(o.text.find("lodbench: 2 cases\n"), std::string::npos) << o.text;
  EXPECT_EQ(o.text.find("shard"), std::string::npos) << o.text;
  o = runCli("run " + lb::test::kTinyConfig + " --dry-run --shard 1/2");
  EXPECT_EQ(o.code, 0) << o.text;
  EXPECT_NE(o.text.find("1 cases (shard 1/2 of 2)"), std::string::npos) << o.text;
}

TEST(Cli, BadFlagsAndInputsExitTwoWithAClearMessage) {
  Out o = runCli("render --path " + kSrc + "/configs/paths/flyover.csv --width 5");
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find("--width"), std::string::npos) << o.text;

  o = runCli("render --path /nonexistent/path.csv --out " + ::testing::TempDir() + "/x.png");
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find("/nonexistent/path.csv"), std::string::npos) << o.text;

  o = runCli("render --path " + kSrc + "/configs/paths/flyover.csv --scheme nope");
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find("unknown scheme 'nope'"), std::string::npos) << o.text;

  o = runCli("render --path " + kSrc + "/configs/paths/flyover.csv --frame 100000");
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find("--frame"), std::string::npos) << o.text;

  std::string bad = ::testing::TempDir() + "/bad_config.json";
  std::ofstream(bad) << "{\n  \"name\": \"x\",\n  \"warmup_frames\": -1\n}\n";
  o = runCli("run " + bad);
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find(bad + ":3"), std::string::npos) << o.text;
  EXPECT_NE(o.text.find("/warmup_frames"), std::string::npos) << o.text;

  o = runCli("frobnicate");
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find("unknown subcommand 'frobnicate'"), std::string::npos) << o.text;
  EXPECT_NE(o.text.find("known: list, devices, run"), std::string::npos) << "lists the subcommands: " << o.text;

  o = runCli("");  // bare: the help, and a usage exit code
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find("Usage"), std::string::npos) << o.text;
}

// With the validation layer missing, a run that asked for validation used to warn and
// go on without it, so "zero validation messages" held vacuously. Hide the layer from the loader.
TEST(Cli, AskedForValidationFailsWithoutTheLayer) {
  const std::string empty = ::testing::TempDir() + "/no_layers";
  std::filesystem::create_directories(empty);
  const std::string out = ::testing::TempDir() + "/no_layer.png";
  std::filesystem::remove(out);
  for (const std::string how : {"LODBENCH_VALIDATION=1", "LODBENCH_VALIDATION=0"}) {
    const std::string cmd = "env " + how + " VK_LAYER_PATH=" + empty + " " + LODBENCH_BINARY + " render --path " +
                            kSrc + "/configs/paths/horizon.csv --width 16 --height 16 --grid 2 --size 17" +
                            (how.back() == '0' ? " --validation" : "") + " --out " + out + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    std::string text;
    std::array<char, 512> buf{};
    while (fgets(buf.data(), int(buf.size()), p)) text += buf.data();
    const int status = pclose(p);
    EXPECT_EQ(WEXITSTATUS(status), 1) << cmd << "\n" << text;
    EXPECT_NE(text.find("VK_LAYER_KHRONOS_validation is not installed"), std::string::npos) << text;
    EXPECT_FALSE(std::filesystem::exists(out)) << "nothing rendered without the requested validation";
  }
  // run: refused before the run directory exists.
  const std::string runDir = ::testing::TempDir() + "/no_layer_run";
  std::filesystem::remove_all(runDir);
  const std::string cmd = "env LODBENCH_VALIDATION=1 VK_LAYER_PATH=" + empty + " " + LODBENCH_BINARY + " run " +
                          lb::test::kTinyConfig + " --quiet --out " + runDir + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  std::string text;
  std::array<char, 512> buf{};
  while (fgets(buf.data(), int(buf.size()), p)) text += buf.data();
  EXPECT_EQ(WEXITSTATUS(pclose(p)), 1) << text;
  EXPECT_NE(text.find("VK_LAYER_KHRONOS_validation is not installed"), std::string::npos) << text;
  EXPECT_FALSE(std::filesystem::exists(runDir));
}

// Render takes every terrain type a config can, r16 / r32f included.
TEST(Cli, RenderLoadsRawTerrains) {
  const std::string dir = ::testing::TempDir();
  std::ofstream(dir + "/t.r16", std::ios::binary) << std::string(2 * 17 * 9, '\x10');
  std::string out = dir + "/raw.png";
  std::filesystem::remove(out);
  Out o = runCli("render --scheme uniform --param level=2 --path " + kSrc +
                 "/configs/paths/horizon.csv --width 32 --height 16 " + "--grid 2 --terrain r16 --terrain-file " + dir +
                 "/t.r16 --terrain-width 17 --terrain-height 9 " + "--height-scale 0.01 --out " + out);
  EXPECT_EQ(o.code, 0) << o.text;
  EXPECT_TRUE(std::filesystem::exists(out)) << o.text;
}

TEST(Cli, RenderWritesAPng) {
  std::string out = ::testing::TempDir() + "/cli_frame.png";
  std::filesystem::remove(out);
  Out o =
      runCli("render --scheme uniform --param level=4 --path " + kSrc +
             "/configs/paths/horizon.csv --frame 3 --width 96 --height 64 --grid 8 --size 65 --heatmap --out " + out);
  EXPECT_EQ(o.code, 0) << o.text;
  EXPECT_NE(o.text.find("64 patches"), std::string::npos) << o.text;
  std::ifstream f(out, std::ios::binary);
  char sig[8] = {};
  f.read(sig, 8);
  EXPECT_EQ(std::string(sig + 1, 3), "PNG");
}
