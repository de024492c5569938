// Configs name schemes together ("all" or a group, schemes/registry.h schemeGroup), so lists that
// grow with every scheme are derived from the registry: a new scheme joins the default job, CI and
// every scenario without an edit to them.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "config/config.h"
#include "input_error.h"
#include "schemes/registry.h"

using namespace lb;

namespace {

const std::string kConfigs = std::string(LODBENCH_SOURCE_DIR) + "/configs";

Config parse(const std::string& schemes) {
  return parseConfig(R"({"name": "t", "paths": ["paths/flyover.csv"], "schemes": )" + schemes + "}", "g.json",
                     kConfigs);
}

std::string errorOf(const std::string& schemes) {
  return lbtest::inputErrorOf([&] { parse(schemes); });
}

std::vector<std::string> names(const Config& c) {
  std::vector<std::string> out;
  for (const SchemeEntry& e : c.schemes) out.push_back(e.name);
  return out;
}

TEST(SchemeGroups, AllIsEverySchemeOfTheRegistryAtItsDefaultsAndNoControl) {
  const Config c = parse(R"(["all"])");
  std::vector<std::string> want;
  for (const Scheme* s : allSchemes()) want.push_back(s->info().name);
  EXPECT_EQ(names(c), want);
  for (const SchemeEntry& e : c.schemes) {
    ASSERT_EQ(e.variants.size(), 1u) << e.name;
    EXPECT_TRUE(e.variants[0].empty()) << e.name;
    EXPECT_EQ(e.field, "/schemes/0");
  }
  EXPECT_EQ(std::count(want.begin(), want.end(), "sphere-copy"), 0);
}

TEST(SchemeGroups, FrontSweepsEachMainParameterOverTheValuesItsSchemeNames) {
  const Config c = parse(R"([{"group": "all", "except": ["reference"], "front": true}])");
  for (const SchemeEntry& e : c.schemes) {
    const SchemeInfo& info = findScheme(e.name)->info();
    ASSERT_EQ(e.variants.size(), info.front.size()) << e.name;
    for (size_t i = 0; i < e.variants.size(); ++i) EXPECT_EQ(e.variants[i].at(info.mainParam), info.front[i]);
  }
  const std::vector<std::string> n = names(c);
  EXPECT_EQ(std::count(n.begin(), n.end(), "reference"), 0);
  // A named entry's "front" is the same sweep.
  const Config one = parse(R"([{"name": "cbt", "front": true}])");
  EXPECT_EQ(one.schemes[0].variants.size(), findScheme("cbt")->info().front.size());
}

// A scheme an entry names keeps that entry (the scenarios' integer 0/1 sweeps): the group leaves it.
TEST(SchemeGroups, ANamedEntryTakesItsSchemeOutOfTheGroup) {
  const Config c =
      parse(R"([{"group": "all", "except": ["reference"]}, {"name": "sphere", "params": {"integer": [0, 1]}}])");
  const std::vector<std::string> n = names(c);
  EXPECT_EQ(std::count(n.begin(), n.end(), "sphere"), 1);
  EXPECT_EQ(c.schemes.back().name, "sphere");
  EXPECT_EQ(c.schemes.back().variants.size(), 2u);
  EXPECT_EQ(c.schemes.back().field, "/schemes/1");
  EXPECT_NO_THROW(expandCases(c));
  // Draw-path groups, and a later group leaves what an earlier one took.
  const Config paths = parse(R"(["instanced-grid", "all"])");
  std::map<std::string, int> count;
  for (const std::string& s : names(paths)) ++count[s];
  for (auto& [s, k] : count) EXPECT_EQ(k, 1) << s;
  EXPECT_EQ(paths.schemes[0].name, "cdlod");
  EXPECT_EQ(parse(R"(["controls"])").schemes.size(), controlSchemes().size());
}

TEST(SchemeGroups, BadGroupsNameFileLineAndField) {
  EXPECT_NE(errorOf(R"([{"group": "alll"}])").find("g.json:1: field '/schemes/0/group': 'alll' is no scheme group"),
            std::string::npos);
  EXPECT_NE(errorOf(R"([{"group": "alll"}])").find("did you mean 'all'"), std::string::npos);
  EXPECT_NE(errorOf(R"([{"group": "instanced-grid", "except": ["sphere"]}])")
                .find("field '/schemes/0/except/0': 'sphere' is not in group 'instanced-grid'"),
            std::string::npos);
  EXPECT_NE(errorOf(R"(["gpu-indirect", "cbt", "cbt-ts"])").find("group 'gpu-indirect' adds no scheme"),
            std::string::npos);
  EXPECT_NE(errorOf(R"([{"group": "all", "name": "sphere"}])").find("not both"), std::string::npos);
  EXPECT_NE(errorOf(R"([{"name": "reference", "front": true}])")
                .find("field '/schemes/0/front': reference has no main parameter to sweep"),
            std::string::npos);
  EXPECT_NE(errorOf(R"([{"name": "sphere", "front": true, "params": {"tri_size": 3}}])")
                .find("'front' sweeps tri_size already"),
            std::string::npos);
  EXPECT_NE(errorOf(R"([{"group": "all", "front": 1}])").find("'/schemes/0/front': expected true or false"),
            std::string::npos);
}

// The lists that used to name every scheme are derived now: the default job, CI and every scenario.
TEST(SchemeGroups, ShippedConfigsNameTheirSchemesByGroup) {
  for (const std::string f : {"/quick.json", "/ci.json", "/scenarios/fast-turn.json", "/scenarios/hostile-flat.json"}) {
    const Config c = loadConfig(kConfigs + f);
    const std::string raw = c.raw["schemes"].dump();
    EXPECT_NE(raw.find("all"), std::string::npos) << f << ": " << raw;
  }
}

}  // namespace
