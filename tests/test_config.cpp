// Config parsing: defaults, expansion into cases, and errors that name file, line and field.
#include <gtest/gtest.h>

#include <set>

#include "error.h"
#include "sweep/config.h"

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

TEST(Config, QuickConfigParses) {
  Config c = loadConfig(kBase + "/quick.json");
  EXPECT_EQ(c.name, "quick");
  ASSERT_EQ(c.schemes.size(), 2u);
  EXPECT_EQ(c.schemes[0].name, "uniform");
  EXPECT_EQ(c.schemes[1].name, "sphere");
  EXPECT_EQ(expandCases(c).size(), 2u);
  EXPECT_EQ(c.resolutions[0], std::make_pair(320, 180));
}

TEST(Config, CartesianProductOfParametersPathsAndTerrains) {
  Config c = parseConfig(R"({
    "name": "t", "paths": ["paths/flyover.csv", "paths/horizon.csv"],
    "terrains": [{"type": "procedural", "seed": [1, 2, 3]}],
    "resolutions": [[64, 64], [128, 64]],
    "schemes": [{"name": "sphere", "params": {"tri_size": [1, 2]}}, "uniform"]
  })", "t.json", kBase);
  auto cases = expandCases(c);
  EXPECT_EQ(cases.size(), 3u * 2u * 2u * (2u + 1u));
  std::set<std::string> ids;
  for (auto& k : cases) ids.insert(k.id);
  EXPECT_EQ(ids.size(), cases.size()) << "case ids are unique";
  EXPECT_EQ(cases[0].params.at("tri_size"), 1.0);
}

TEST(Config, ErrorsNameFileLineAndField) {
  std::string e = errorOf("{\n  \"name\": \"x\",\n  \"paths\": [\"paths/flyover.csv\"],\n  \"grid\": \"big\",\n"
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
  std::string e = errorOf("{\n \"paths\": [\"paths/flyover.csv\"],\n \"schemes\": [\n  \"sphere\",\n"
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
