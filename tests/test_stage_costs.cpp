// run.json costs.terrains: a kept terrain's later cases take its heights and normal map from the
// cache, so the stage figures are each stage's largest over the cases, the one that did the work.
#include <gtest/gtest.h>

#include "replay/run_case.h"

using namespace lb;

TEST(StageCosts, EachStageKeepsTheCaseThatDidTheWork) {
  clearStageCosts();
  recordStageCosts("t", "cdlod", 12.5, 3.0, 8.0, 0.7);     // the first case loads everything
  recordStageCosts("t", "cbt", 0.0001, 3.1, 0.0, 0.04);    // a later one: cached heights and normals
  recordStageCosts("t", "cdlod", 0.0001, 2.9, 0.0, 0.01);  // cdlod again: its table from the cache
  const nlohmann::json j = stageCostsJson();
  ASSERT_TRUE(j.contains("t"));
  EXPECT_DOUBLE_EQ(j["t"]["load_s"].get<double>(), 12.5);
  EXPECT_DOUBLE_EQ(j["t"]["pages_s"].get<double>(), 3.1);
  EXPECT_DOUBLE_EQ(j["t"]["normal_map_s"].get<double>(), 8.0);
  EXPECT_DOUBLE_EQ(j["t"]["preprocess_s"]["cdlod"].get<double>(), 0.7);
  EXPECT_DOUBLE_EQ(j["t"]["preprocess_s"]["cbt"].get<double>(), 0.04);
  clearStageCosts();
  EXPECT_TRUE(stageCostsJson().empty());
}
