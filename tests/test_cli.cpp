// The lodbench binary: --help everywhere, exit codes, and errors that name the bad input.
#include <gtest/gtest.h>

#include "cli_run.h"

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

using Out = lb::test::CliOut;

// Keeps the validation layer as ctest sets it.
Out runCli(const std::string& args) { return lb::test::lodbench(args, false); }

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
  EXPECT_NE(o.text.find("tri_size   default 3"), std::string::npos) << o.text;
  EXPECT_NE(o.text.find("range [1, 64]"), std::string::npos) << o.text;
}

TEST(Cli, BadFlagsAndInputsExitTwoWithAClearMessage) {
  Out o = runCli("render --path " + kSrc + "/configs/paths/flyover.csv --width 5");
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find("--width"), std::string::npos) << o.text;

  o = runCli("render --path /nonexistent/path.csv");
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
}

TEST(Cli, RenderWritesAPng) {
  std::string out = ::testing::TempDir() + "/cli_frame.png";
  std::filesystem::remove(out);
  Out o = runCli("render --scheme uniform --param level=4 --path " + kSrc +
                 "/configs/paths/horizon.csv --frame 3 --width 96 --height 64 --grid 8 --size 65 --heatmap --out " + out);
  EXPECT_EQ(o.code, 0) << o.text;
  EXPECT_NE(o.text.find("64 patches"), std::string::npos) << o.text;
  std::ifstream f(out, std::ios::binary);
  char sig[8] = {};
  f.read(sig, 8);
  EXPECT_EQ(std::string(sig + 1, 3), "PNG");
}
