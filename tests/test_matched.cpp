// The matched search (replay/matched.h) around trials that cannot run: each is recorded with its
// reason and the search goes on; the case fails only when no trial runs.
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "camera/camera_path.h"
#include "config/config.h"
#include "gpu_fixture.h"
#include "gpu_lod_scheme.h"
#include "replay/matched.h"

using namespace lb;
using namespace lbtest;

namespace {

// gpuUniformScheme with a planted pool: levels above `limit` cannot run (as a tree past its pool
// or a device limit), with a reason.
class FinitePool : public Scheme {
 public:
  explicit FinitePool(double limit) : limit_(limit) {}
  const SchemeInfo& info() const override { return gpuUniformScheme().info(); }
  GpuLod gpuLod(const Heightfield& hf, const ParamValues& v, const GpuLodBudget& budget) const override {
    if (v.at("level") > limit_)
      throw std::runtime_error("planted pool overflow at level " + std::to_string(int(v.at("level"))));
    return gpuUniformScheme().gpuLod(hf, v, budget);
  }

 private:
  double limit_;
};

struct Search {
  Config config;
  Case c;
  CameraPath path;
};

Search search(double target) {
  Search s;
  s.config.fps = 10;
  s.config.maxFrames = 6;
  s.config.match = {"err_mean_px", target, 2, 8};
  s.config.measure.compute = "cpu";
  s.c.width = 96, s.c.height = 64, s.c.grid = 8;
  s.path = loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/flyover.csv");
  return s;
}

void print(const char* what, const MatchResult& m) {
  std::printf("[matched] %s: %s %g -> %g (%s)\n", what, m.param.c_str(), m.value, m.achieved,
              m.reachable ? "reachable" : "unreachable");
  for (const MatchTrial& t : m.trials) std::printf("  %g: %g %s\n", t.value, t.achieved, t.reason.c_str());
}

int failed(const MatchResult& m) {
  int n = 0;
  for (const MatchTrial& t : m.trials) n += std::isnan(t.achieved);
  return n;
}

}  // namespace

class Matched : public GpuTest {};

TEST_F(Matched, TrialsThatCannotRunAreRecordedAndTheSearchGoesOn) {
  const Heightfield& hf = testTerrain();
  // The error of every level that runs, for the targets below.
  Search s = search(0.1);
  const MatchResult free = matchParameter(gpu(), gpuUniformScheme(), {{"level", 8}}, hf, s.path, s.config, s.c);
  print("no pool", free);
  ASSERT_TRUE(free.reachable);
  EXPECT_EQ(failed(free), 0);
  EXPECT_EQ(int(free.trials.size()), free.evaluations);

  // The same target with levels above 20 failing: the top end moves inwards, the target is still met.
  const FinitePool pool(20);
  const MatchResult m = matchParameter(gpu(), pool, {{"level", 8}}, hf, s.path, s.config, s.c);
  print("pool 20", m);
  EXPECT_GE(failed(m), 1) << "level 64 must have been tried and failed";
  EXPECT_EQ(int(m.trials.size()), m.evaluations);
  for (const MatchTrial& t : m.trials)
    if (std::isnan(t.achieved)) EXPECT_NE(t.reason.find("planted pool overflow"), std::string::npos) << t.reason;
  EXPECT_TRUE(m.reachable);
  EXPECT_LE(m.value, 20);
  EXPECT_NEAR(m.achieved, free.achieved, 0.25 * free.achieved);

  // A target only levels past the pool reach: unreachable, stating the closest level that ran.
  Search fine = search(0.002);
  const MatchResult u = matchParameter(gpu(), pool, {{"level", 8}}, hf, fine.path, fine.config, fine.c);
  print("pool 20, fine target", u);
  EXPECT_FALSE(u.reachable);
  EXPECT_LE(u.value, 20);
  EXPECT_GE(u.value, 10) << "the closest configuration that ran is the finest that ran";
  EXPECT_FALSE(std::isnan(u.achieved));

  // No level runs: the case fails, naming why.
  const FinitePool none(0);
  try {
    matchParameter(gpu(), none, {{"level", 8}}, hf, s.path, s.config, s.c);
    ADD_FAILURE() << "a search with no runnable trial returned";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no value of 'level' runs"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("planted pool overflow"), std::string::npos) << e.what();
  }
}
