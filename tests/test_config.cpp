// Config parsing: defaults, expansion into cases, and errors that name file, line and field.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>

#include "config/config.h"
#include "error.h"
#include "schemes/registry.h"

using namespace lb;

static const std::string kBase = std::string(LODBENCH_SOURCE_DIR) + "/configs";

static std::string errorOf(const std::string& text) {
  try {
    parseConfig(text, "bad.json", kBase);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The default job is the whole comparison: every registered scheme but reference (level
// 64 everywhere, ~15 s a frame on lavapipe) with at least 3 values of one parameter, so each has a
// front, over one path at lavapipe size.
TEST(Config, QuickConfigRunsEverySchemeWithAFront) {
  Config c = loadConfig(kBase + "/quick.json");
  EXPECT_EQ(c.name, "quick");
  std::map<std::string, size_t> variants;
  for (auto& e : c.schemes) variants[e.name] += e.variants.size();
  for (const Scheme* s : allSchemes()) {
    const std::string& name = s->info().name;
    if (name == "reference") continue;
    EXPECT_GE(variants[name], 3u) << name << " needs a sweep of its main parameter in quick.json";
  }
  EXPECT_EQ(variants.count("reference"), 0u) << "update the test and quick.json's description together";
  EXPECT_EQ(c.paths.size(), 1u);
  EXPECT_EQ(c.resolutions.size(), 1u);
  EXPECT_LE(c.resolutions[0].first * c.resolutions[0].second, 320 * 180);
  EXPECT_GT(c.measure.every, 0);
  EXPECT_EQ(expandCases(c).size(), 3 * (allSchemes().size() - 1));
}

TEST(Config, CartesianProductOfParametersPathsAndTerrains) {
  Config c = parseConfig(R"({
    "name": "t", "paths": ["paths/flyover.csv", "paths/horizon.csv"],
    "terrains": [{"type": "procedural", "seed": [1, 2, 3]}],
    "resolutions": [[64, 64], [128, 64]],
    "schemes": [{"name": "sphere", "params": {"tri_size": [1, 2]}}, "uniform"]
  })",
                         "t.json", kBase);
  auto cases = expandCases(c);
  EXPECT_EQ(cases.size(), 3u * 2u * 2u * (2u + 1u));
  std::set<std::string> ids;
  for (auto& k : cases) ids.insert(k.id);
  EXPECT_EQ(ids.size(), cases.size()) << "case ids are unique";
  EXPECT_EQ(cases[0].params.at("tri_size"), 1.0);
}

TEST(Config, GridsMakeOneCasePerGridWithTheGridInIdAndDigest) {
  const char* one = R"({"name": "t", "paths": ["paths/flyover.csv"], "grid": 64, "schemes": ["sphere"]})";
  Config c1 = parseConfig(one, "t.json", kBase);
  Config c = parseConfig(R"({"name": "t", "paths": ["paths/flyover.csv"], "grids": [64, 128],
    "schemes": ["sphere", "uniform"]})",
                         "t.json", kBase);
  auto cases = expandCases(c);
  ASSERT_EQ(cases.size(), 4u);
  EXPECT_EQ(cases[0].grid, 64);
  EXPECT_EQ(cases[2].grid, 128);
  EXPECT_EQ(cases[2].id, "sphere_proc1024s1_flyover_320x180_g128");
  EXPECT_EQ(cases[2].inputs["measurement"]["grid"], 128);
  EXPECT_NE(cases[0].digest, cases[2].digest);
  // A single grid keeps the readable id and the digest a "grid" config always had.
  auto single = expandCases(c1);
  EXPECT_EQ(single[0].id, "sphere_proc1024s1_flyover_320x180");
  EXPECT_EQ(single[0].digest, cases[0].digest);
  EXPECT_NE(errorOf(R"({"name": "t", "paths": ["paths/flyover.csv"], "grid": 64, "grids": [64],
    "schemes": ["sphere"]})")
                .find("/grids"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"name": "t", "paths": ["paths/flyover.csv"], "grids": [64, 64],
    "schemes": ["sphere"]})")
                .find("field '/grids/1': grid listed twice"),
            std::string::npos);
}

TEST(Config, ErrorsNameFileLineAndField) {
  std::string e = errorOf(
      "{\n  \"name\": \"x\",\n  \"paths\": [\"paths/flyover.csv\"],\n  \"grid\": \"big\",\n"
      "  \"schemes\": [\"sphere\"]\n}");
  EXPECT_NE(e.find("bad.json:4"), std::string::npos) << e;
  EXPECT_NE(e.find("/grid"), std::string::npos) << e;
  EXPECT_NE(e.find("expected a number"), std::string::npos) << e;
}

TEST(Config, MalformedInputsAreRejectedClearly) {
  struct Bad {
    const char* text;
    const char* expect;
  };
  const Bad cases[] = {
      {"{\n\"name\": \"x\",\n\"schemes\": [\"sphere\"]\n", "bad.json:4"},  // truncated JSON: line of the error
      {"{\"paths\": [\"paths/flyover.csv\"], \"schemes\": [\"nope\"]}", "unknown scheme 'nope'"},
      {"{\"paths\": [\"paths/flyover.csv\"], \"schemes\": []}", "/schemes"},
      {"{\"schemes\": [\"sphere\"]}", "no camera path"},
      {"{\"paths\": [\"paths/missing.csv\"], \"schemes\": [\"sphere\"]}", "cannot open camera path"},
      {"{\"paths\": [\"paths/flyover.csv\"], \"schemes\": [\"sphere\"], \"gird\": 3}", "/gird': unknown key"},
      {"{\"paths\": [\"paths/flyover.csv\"], \"schemes\": [{\"name\": \"sphere\", \"params\": {\"tri_size\": 0}}]}",
       "/schemes/0/params/tri_size"},
      {"{\"paths\": [\"paths/flyover.csv\"], \"schemes\": [{\"name\": \"uniform\", \"params\": {\"level\": 2.5}}]}",
       "must be an integer"},
      {"{\"paths\": [\"paths/flyover.csv\"], \"schemes\": [{\"name\": \"uniform\", \"params\": {\"lvl\": 2}}]}",
       "has no parameter 'lvl'"},
      {"{\"paths\": [\"paths/flyover.csv\"], \"schemes\": [\"sphere\"], \"resolution\": [10, 10]}", "/resolution/0"},
      {"{\"paths\": [\"paths/flyover.csv\"], \"schemes\": [\"sphere\"], \"terrain\": {\"type\": \"hgt\"}}",
       "needs a 'file'"},
      {"{\"paths\": [\"paths/flyover.csv\"], \"schemes\": [\"sphere\"], \"terrain\": {\"type\": \"tiff\"}}",
       "/terrain/type"},
      {"{\"paths\": [\"paths/flyover.csv\"], \"schemes\": [\"sphere\"], \"images\": {\"modes\": [\"x\"]}}",
       "/images/modes/0"},
      {"[1, 2]", "expected an object"},
  };
  for (auto& b : cases) {
    std::string e = errorOf(b.text);
    EXPECT_NE(e.find(b.expect), std::string::npos) << "input: " << b.text << "\nerror: " << e;
    EXPECT_NE(e.find("bad.json"), std::string::npos) << e;
  }
}

TEST(Config, FieldLineIsReported) {
  std::string e = errorOf(
      "{\n \"paths\": [\"paths/flyover.csv\"],\n \"schemes\": [\n  \"sphere\",\n"
      "  {\"name\": \"uniform\",\n   \"params\": {\"level\": 99}}\n ]\n}");
  EXPECT_NE(e.find("bad.json:6"), std::string::npos) << e;
  EXPECT_NE(e.find("[1, 64]"), std::string::npos) << e;
}

TEST(Config, MissingFile) {
  try {
    loadConfig("/nonexistent/x.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/x.json"), std::string::npos);
  }
}

// Last-wins duplicate keys hid typos; now the second occurrence is named.
TEST(Config, DuplicateKeysAreRejectedWithTheirLine) {
  std::string e = errorOf(
      "{\n \"paths\": [\"paths/flyover.csv\"],\n \"schemes\": [{\"name\": \"sphere\",\n"
      "   \"params\": {\"tri_size\": 2,\n  \"tri_size\": 3}}]\n}");
  EXPECT_NE(e.find("bad.json:5"), std::string::npos) << e;
  EXPECT_NE(e.find("'/schemes/0/params/tri_size': duplicate key"), std::string::npos) << e;
  // The same key in two different objects is fine.
  EXPECT_EQ(
      errorOf("{\"paths\": [\"paths/flyover.csv\"], \"schemes\": [{\"name\": \"sphere\"}, {\"name\": \"uniform\"}]}"),
      "");
}

// A path CSV is parsed with the config, so a malformed one stops the run before any case.
TEST(Config, CameraPathErrorsAreFoundAtConfigTime) {
  const std::string dir = ::testing::TempDir();
  std::ofstream(dir + "/broken.csv")
      << "time,eye_x,eye_y,eye_z,target_x,target_y,target_z,fov\n0,0,0,0,1,0,1,60\n1,oops,0,0,1,0,1,60\n";
  try {
    parseConfig("{\"paths\": [\"broken.csv\"],\n \"schemes\": [\"sphere\"]}", "c.json", dir);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("c.json:1: field '/paths/0'"), std::string::npos) << m;
    EXPECT_NE(m.find("broken.csv:3: column 'eye_x'"), std::string::npos) << m;
  }
  EXPECT_NE(errorOf("{\"paths\": [\"paths\"], \"schemes\": [\"sphere\"]}").find("is a directory"), std::string::npos);
}

// Fields a terrain type does not read, and image frames past the path, were silently ignored.
TEST(Config, IgnoredFieldsAndUnreachableFramesAreRejected) {
  const std::string p = "\"paths\": [\"paths/horizon.csv\"], \"schemes\": [\"sphere\"], ";
  EXPECT_NE(errorOf("{" + p + "\"terrain\": {\"type\": \"procedural\", \"width\": 3}}").find("'/terrain/width'"),
            std::string::npos);
  EXPECT_NE(errorOf("{" + p + "\"terrain\": {\"type\": \"hgt\", \"file\": \"quick.json\", \"seed\": 3}}")
                .find("'/terrain/seed': terrain type 'hgt' does not use 'seed'"),
            std::string::npos);
  Config c = parseConfig("{" + p + "\"max_frames\": 10, \"images\": {\"frames\": [0, 9, -10]}}", "ok.json", kBase);
  EXPECT_EQ(c.images.frames.size(), 3u);
  EXPECT_NE(errorOf("{" + p + "\"max_frames\": 10, \"images\": {\"frames\": [0, 10]}}").find("'/images/frames/1'"),
            std::string::npos);
  EXPECT_NE(errorOf("{" + p + "\"images\": {\"frames\": [-100000]}}").find("'/images/frames/0'"), std::string::npos);
}

// Interlock accepted dmin == dmax, which distance rejects; the range rule is now one for all.
TEST(Config, EmptyDistanceRangesAreRejectedForEveryScheme) {
  for (const char* scheme : {"distance", "interlock", "planefit"}) {
    std::string e = errorOf(std::string("{\"paths\": [\"paths/flyover.csv\"], \"schemes\": [{\"name\": \"") + scheme +
                            "\", \"params\": {\"dmin\": 0.7, \"dmax\": 0.7}}]}");
    EXPECT_NE(e.find("/schemes/0/params"), std::string::npos) << scheme << ": " << e;
    EXPECT_NE(e.find("dmin"), std::string::npos) << scheme << ": " << e;
  }
}
