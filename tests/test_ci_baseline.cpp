// configs/ci.json covers every registered scheme, and the committed baseline matches it case for
// case (so adding a scheme fails here until scripts/refresh-baseline.sh records it).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "compare/run_data.h"
#include "config/config.h"
#include "schemes/registry.h"

namespace lb {
namespace {

const std::string kSrc = LODBENCH_SOURCE_DIR;

TEST(CiBaseline, ConfigCoversEverySchemeInTheRegistry) {
  Config c = loadConfig(kSrc + "/configs/ci.json");
  std::set<std::string> inConfig, registered;
  for (auto& s : c.schemes) inConfig.insert(s.name);
  for (const Scheme* s : allSchemes()) registered.insert(s->info().name);
  EXPECT_EQ(inConfig, registered) << "add the new scheme to configs/ci.json and run scripts/refresh-baseline.sh";
}

TEST(CiBaseline, BaselineHasEveryCaseOfTheConfig) {
  Config c = loadConfig(kSrc + "/configs/ci.json");
  // A single run, or (for timing verdicts) a folder of rounds r1/, r2/, r3/.
  RunData base = poolRuns(loadRounds(kSrc + "/results/baseline/ci"));
  std::set<std::string> expected, recorded;
  for (auto& k : expandCases(c)) expected.insert(k.id);
  for (auto& [id, data] : base.cases) {
    recorded.insert(id);
    // A mesh-shader scheme's cases are recorded as skipped on the baseline's device (lavapipe lacks
    // VK_EXT_mesh_shader); every other case must have run.
    const Scheme* scheme = findScheme(data.scheme);
    if (scheme && scheme->info().path == DrawPath::Mesh && data.status == "skipped") {
      EXPECT_NE(data.reason.find("lacks VK_EXT_mesh_shader"), std::string::npos) << id << ": " << data.reason;
      continue;
    }
    EXPECT_EQ(data.status, "ok") << id << ": " << data.reason;
  }
  EXPECT_EQ(recorded, expected) << "configs/ci.json changed: run scripts/refresh-baseline.sh";
  EXPECT_EQ(base.context["tool"], "lodbench");
}

}  // namespace
}  // namespace lb
