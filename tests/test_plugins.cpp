// Scheme plugins (docs/plugins.md) through the binary, with the plugins this build makes
// (CMakeLists.txt: the example's own-sphere built in-tree, and broken ones): a plugin scheme runs
// like its built-in twin frame for frame, its library is part of its cases' identity, report and
// compare take it, and each bad plugin is a clear error that writes nothing. The same example
// built against an installed package: test_plugin_install.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli_run.h"
#include "plugin_twin.h"
#include "schemes/plugin_api.h"

namespace fs = std::filesystem;
using lb::test::CliOut;
using nlohmann::json;

namespace {

const std::string kPlugins = LODBENCH_TEST_PLUGIN_DIR;
const std::string kOwnScheme = kPlugins + "/libown_scheme.so";
using lb::test::expectSameFrames;
using lb::test::twinConfig;
using lb::test::writeConfig;

// An error (exit 2) that says `what`, and no run folder.
void expectRefused(const std::string& args, const std::string& what, const std::string& out) {
  CliOut o = lb::test::lodbench(args + " --out " + out);
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find(what), std::string::npos) << o.text;
  EXPECT_FALSE(fs::exists(out)) << "a refused plugin wrote " << out;
}

class Plugins : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!LODBENCH_PLUGINS_BUILT) GTEST_SKIP() << "this build loads no plugins (LODBENCH_STATIC_RUNTIME or fuzzing)";
  }
};

TEST_F(Plugins, PluginSchemeMatchesItsBuiltInTwinOnEveryFrame) {
  const std::string dir = lb::test::freshDir("plugin_twin");
  const std::string config = writeConfig(dir, twinConfig(kOwnScheme));
  CliOut o = lb::test::lodbench("run " + config + " --out " + dir + "/run -q", /*timing=*/false);
  ASSERT_EQ(o.code, 0) << o.text;
  expectSameFrames(dir + "/run", "sphere", "own-sphere");
  const json run = lb::test::readJson(dir + "/run/run.json");
  EXPECT_EQ(run["validation_errors"], 0);
  ASSERT_EQ(run["context"]["plugins"].size(), 1u);
  EXPECT_EQ(run["context"]["plugins"][0]["schemes"], json({"own-sphere"}));
}

TEST_F(Plugins, PluginFileDigestAndApiVersionAreInTheCaseIdentityAndARebuildRerunsItsCases) {
  const std::string dir = lb::test::freshDir("plugin_rebuilt");
  fs::create_directories(dir);
  const std::string lib = dir + "/libown_scheme.so";
  fs::copy_file(kOwnScheme, lib);
  const std::string config = writeConfig(dir, twinConfig("libown_scheme.so"));  // relative to the config
  ASSERT_EQ(lb::test::lodbench("run " + config + " --out " + dir + "/run -q").code, 0);
  const json before = lb::test::readJson(dir + "/run/cases/own-sphere_proc65s1_flyover_64x36.json");
  EXPECT_EQ(before["inputs"]["plugin"]["sha256"],
            lb::test::shell("sha256sum " + lib + " | cut -c1-64").text.substr(0, 64));
  EXPECT_EQ(before["inputs"]["plugin"]["api_version"], LODBENCH_PLUGIN_API_VERSION);
  EXPECT_FALSE(lb::test::readJson(dir + "/run/cases/sphere_proc65s1_flyover_64x36.json")["inputs"].contains("plugin"));
  // The same library again: both cases kept.
  CliOut same = lb::test::lodbench("run " + config + " --out " + dir + "/run");
  EXPECT_NE(same.text.find("2 ok (2 resumed)"), std::string::npos) << same.text;
  // A rebuilt library (other bytes): its case runs again without being asked, the built-in one is kept.
  std::ofstream(lib, std::ios::app) << "rebuilt";
  CliOut rebuilt = lb::test::lodbench("run " + config + " --out " + dir + "/run");
  EXPECT_EQ(rebuilt.code, 0) << rebuilt.text;
  EXPECT_NE(rebuilt.text.find("rerunning case of a rebuilt plugin own-sphere"), std::string::npos) << rebuilt.text;
  EXPECT_NE(rebuilt.text.find("2 ok (1 resumed)"), std::string::npos) << rebuilt.text;
  const json after = lb::test::readJson(dir + "/run/cases/own-sphere_proc65s1_flyover_64x36.json");
  EXPECT_NE(after["digest"], before["digest"]);
}

TEST_F(Plugins, ReportCompareAndGroupsTakeAPluginScheme) {
  const std::string dir = lb::test::freshDir("plugin_report");
  json config = twinConfig(kOwnScheme);
  config["schemes"] = {"all"};  // a group takes the plugin's scheme like a built-in one
  CliOut dry = lb::test::lodbench("run " + writeConfig(dir + "/all", config) + " --dry-run");
  EXPECT_NE(dry.text.find("own-sphere_proc65s1"), std::string::npos) << dry.text;
  EXPECT_NE(dry.text.find("cdlod_proc65s1"), std::string::npos) << dry.text;
  config["schemes"] = {"sphere", "own-sphere"};
  config["measure"] = {{"every", 2}, {"passes", {"error"}}};
  ASSERT_EQ(lb::test::lodbench("run " + writeConfig(dir, config) + " --out " + dir + "/run -q").code, 0);
  // The report loads the plugin the run recorded: its scheme has its draw path and its own colour.
  CliOut report = lb::test::lodbench("report " + dir + "/run --no-html");
  ASSERT_EQ(report.code, 0) << report.text;
  EXPECT_EQ(report.text.find("not loaded"), std::string::npos) << report.text;
  std::ifstream md(dir + "/run/report/report.md");
  const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("own-sphere"), std::string::npos);
  CliOut compare = lb::test::lodbench("compare " + dir + "/run " + dir + "/run --require-exact");
  EXPECT_EQ(compare.code, 0) << compare.text;
  EXPECT_NE(compare.text.find("no regression (2 cases)"), std::string::npos) << compare.text;
}

TEST_F(Plugins, BadPluginsAreClearErrorsThatWriteNothing) {
  const std::string dir = lb::test::freshDir("plugin_bad");
  const std::string tiny = lb::test::kTinyConfig;
  expectRefused("run " + tiny + " --plugin " + kPlugins + "/libmissing.so", "libmissing.so': no such file", dir + "/a");
  expectRefused("run " + tiny + " --plugin " + kPlugins + "/libno_symbol.so",
                "exports no registration function lodbench_plugin", dir + "/b");
  expectRefused("run " + tiny + " --plugin " + kPlugins + "/libwrong_api.so",
                "was built against plugin API " + std::to_string(LODBENCH_PLUGIN_API_VERSION + 1) +
                    " (lodbench 9.9.9), this lodbench speaks plugin API " +
                    std::to_string(LODBENCH_PLUGIN_API_VERSION) + " (lodbench ",
                dir + "/c");
  expectRefused("run " + tiny + " --plugin " + kPlugins + "/libcollides.so",
                "scheme 'sphere' has the name of a built-in scheme", dir + "/d");
  // A file that is no library at all: the loader's own reason.
  std::ofstream(dir + "_notalib.so") << "not a library";
  expectRefused("run " + tiny + " --plugin " + dir + "_notalib.so", "cannot load it:", dir + "/e");
}

// Named in a config: the error names the file, line and field.
TEST_F(Plugins, ConfigPluginErrorsNameFileLineAndField) {
  const std::string dir = lb::test::freshDir("plugin_config_bad");
  json config = twinConfig(kPlugins + "/libwrong_api.so");
  const std::string file = writeConfig(dir, config);
  CliOut o = lb::test::lodbench("run " + file + " --out " + dir + "/run");
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find(file + ":"), std::string::npos) << o.text;
  EXPECT_NE(o.text.find("field '/plugins/0': plugin '"), std::string::npos) << o.text;
  EXPECT_NE(o.text.find("plugin API " + std::to_string(LODBENCH_PLUGIN_API_VERSION + 1)), std::string::npos) << o.text;
  EXPECT_FALSE(fs::exists(dir + "/run"));
}

}  // namespace
