// The installed package as a user meets it (docs/plugins.md): `cmake --install` of this build into a
// temporary prefix, examples/own-scheme built against it in a build tree of its own, and the
// installed binary running that plugin next to its in-tree twin, sphere: every frame's counters,
// histogram and errors equal, report and compare taking it like any scheme. And a plugin whose
// shader does not compile fails its own build with the compiler's message, leaving no library.
// Release pass only (scripts/test.sh): the sanitizer pass loads the same plugin code through
// test_plugins.cpp, and would pay a second compile of the example for nothing new. A plugin on the
// mesh path compiles its task and mesh shaders and is skipped with the reason where the device lacks
// them, as the built-in mesh schemes are.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli_run.h"
#include "plugin_twin.h"

namespace fs = std::filesystem;
using lb::test::CliOut;
using lb::test::shell;

namespace {

const std::string kSrc = LODBENCH_SOURCE_DIR;

class PluginInstall : public ::testing::Test {
 protected:
  void SetUp() override {
    if (LODBENCH_SANITIZE_BUILD) GTEST_SKIP() << "Release pass only (test_plugins.cpp covers the loader under ASan)";
    if (!LODBENCH_PLUGINS_BUILT) GTEST_SKIP() << "this build loads no plugins (LODBENCH_STATIC_RUNTIME or fuzzing)";
    dir_ = lb::test::freshDir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    prefix_ = dir_ + "/prefix";
    CliOut install = shell("cmake --install '" + std::string(LODBENCH_BUILD_DIR) + "' --prefix '" + prefix_ + "'");
    ASSERT_EQ(install.code, 0) << install.text;
  }
  // Configure and build a plugin project against the prefix, as its README says.
  CliOut buildPlugin(const std::string& source, const std::string& build) {
    CliOut configure = shell("cmake -S '" + source + "' -B '" + build + "' -DCMAKE_PREFIX_PATH='" + prefix_ + "'");
    if (configure.code != 0) return configure;
    return shell("cmake --build '" + build + "' -j2");
  }
  std::string installed(const std::string& args) {  // validation as ctest sets it
    return prefix_ + "/bin/lodbench " + args;
  }
  std::string dir_, prefix_;
};

TEST_F(PluginInstall, ExampleBuiltAgainstTheInstalledPackageRunsLikeItsInTreeTwin) {
  for (const char* f : {"bin/lodbench", "lib/cmake/lodbench/lodbenchConfig.cmake",
                        "lib/cmake/lodbench/LodbenchScheme.cmake", "include/lodbench/schemes/plugin_api.h",
                        "include/lodbench/render/scheme.h", "include/lodbench/shaders/common.glsl",
                        "include/lodbench/shaders/sphere.tesc", "share/lodbench/spirv/terrain.vert.spv"})
    EXPECT_TRUE(fs::exists(prefix_ + "/" + f)) << f;
  const std::string build = dir_ + "/own-scheme-build";
  CliOut b = buildPlugin(kSrc + "/examples/own-scheme", build);
  ASSERT_EQ(b.code, 0) << b.text;
  const std::string lib = build + "/libown_scheme.so";
  ASSERT_TRUE(fs::exists(lib)) << b.text;

  const std::string config = lb::test::writeConfig(dir_, lb::test::twinConfig(lib));
  CliOut run = shell(installed("run " + config + " --out " + dir_ + "/run -q"));
  ASSERT_EQ(run.code, 0) << run.text;
  lb::test::expectSameFrames(dir_ + "/run", "sphere", "own-sphere");
  EXPECT_EQ(lb::test::readJson(dir_ + "/run/run.json")["validation_errors"], 0);

  CliOut report = shell(installed("report " + dir_ + "/run --no-html"));
  ASSERT_EQ(report.code, 0) << report.text;
  std::ifstream md(dir_ + "/run/report/report.md");
  const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("own-sphere"), std::string::npos);
  CliOut compare = shell(installed("compare " + dir_ + "/run " + dir_ + "/run --require-exact"));
  EXPECT_EQ(compare.code, 0) << compare.text;
}

TEST_F(PluginInstall, AShaderThatDoesNotCompileFailsThePluginBuildWithTheCompilerMessage) {
  const std::string build = dir_ + "/broken-build";
  CliOut b = buildPlugin(kSrc + "/tests/plugins/broken-shader", build);
  EXPECT_NE(b.code, 0) << b.text;
  EXPECT_NE(b.text.find("own_sphere.tesc:9: 'undefinedTriangleSize' : undeclared identifier"), std::string::npos)
      << b.text;
  EXPECT_FALSE(fs::exists(build + "/libbroken.so"));
}

TEST_F(PluginInstall, AMeshPathPluginBuildsItsTaskAndMeshShadersAndLoadsLikeTheBuiltInMeshSchemes) {
  const std::string build = dir_ + "/mesh-build";
  CliOut b = buildPlugin(kSrc + "/tests/plugins/mesh-stages", build);
  ASSERT_EQ(b.code, 0) << b.text;
  const std::string lib = build + "/libmesh_stages.so";
  ASSERT_TRUE(fs::exists(lib)) << b.text;
  nlohmann::json cfg = lb::test::twinConfig(lib);
  cfg["schemes"] = {"mesh-stages"};
  cfg["measure"] = {{"every", 1}, {"passes", nlohmann::json::array()}};
  CliOut run = shell(installed("run " + lb::test::writeConfig(dir_, cfg) + " --out " + dir_ + "/run -q"));
  ASSERT_EQ(run.code, 0) << run.text;
  const nlohmann::json c = lb::test::readJson(dir_ + "/run/cases/mesh-stages_proc65s1_flyover_64x36.json");
  CliOut devices = shell(installed("devices"));
  if (devices.text.find("mesh shaders: yes") == std::string::npos) {
    EXPECT_EQ(c["status"], "skipped") << c.dump();
    EXPECT_NE(c["reason"].get<std::string>().find("lacks VK_EXT_mesh_shader"), std::string::npos) << c["reason"];
  } else {
    EXPECT_EQ(c["status"], "ok") << c["reason"];
  }
}

}  // namespace
