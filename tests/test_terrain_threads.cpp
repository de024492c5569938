// The terrain passes split rows across threads (terrain/parallel_rows.h): the thread count must
// change the time only, never a bit of the output. And "detail": "resolution" must leave sizes
// whose octave count stays 8 exactly as the default generator makes them.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <string>

#include "schemes/preprocess/density_map.h"
#include "schemes/preprocess/plane_fit.h"
#include "schemes/preprocess/tess_deviation.h"
#include "schemes/registry.h"
#include "terrain/heightfield.h"
#include "terrain/normal_map.h"
#include "terrain/parallel_rows.h"

using namespace lb;

namespace {

// Sets LODBENCH_THREADS for the scope, restoring the previous value after.
struct ThreadsEnv {
  std::string old;
  bool had;
  explicit ThreadsEnv(int n) {
    const char* v = std::getenv("LODBENCH_THREADS");
    had = v != nullptr;
    if (had) old = v;
    setenv("LODBENCH_THREADS", std::to_string(n).c_str(), 1);
  }
  ~ThreadsEnv() {
    if (had)
      setenv("LODBENCH_THREADS", old.c_str(), 1);
    else
      unsetenv("LODBENCH_THREADS");
  }
};

template <typename T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

struct Outputs {
  Heightfield hf;
  NormalMap normals;
  std::vector<float> density;
  PlaneFitResult book, lsq;
  DeviationTable dev;
};

Outputs compute(int threads) {
  ThreadsEnv env(threads);
  TerrainSpec spec;
  spec.size = 700;  // > 256 rows per band for 2 threads, uneven bands for 3
  spec.seed = 5;
  Outputs o;
  o.hf = makeProcedural(spec);
  o.normals = computeNormalMap(o.hf);
  o.density = densityMap(o.hf, 0.0f, 40.0f);
  o.book = fitPlanes(o.hf, PlaneFit::Book);
  o.lsq = fitPlanes(o.hf, PlaneFit::LeastSquares);
  o.dev = tessDeviation(o.hf, 8);
  return o;
}

}  // namespace

TEST(TerrainThreads, EveryPassIsBitIdenticalOnOneAndManyThreads) {
  const Outputs one = compute(1);
  for (int threads : {2, 3, 8}) {
    const Outputs many = compute(threads);
    EXPECT_TRUE(sameBytes(one.hf.h, many.hf.h)) << threads << " threads: heights";
    EXPECT_TRUE(sameBytes(one.normals.texels, many.normals.texels)) << threads << " threads: normal map";
    EXPECT_TRUE(sameBytes(one.density, many.density)) << threads << " threads: density map";
    ASSERT_EQ(one.book.blocks.size(), many.book.blocks.size());
    EXPECT_EQ(
        std::memcmp(one.book.blocks.data(), many.book.blocks.data(), one.book.blocks.size() * sizeof(PlaneFitBlock)),
        0);
    EXPECT_EQ(std::memcmp(one.lsq.blocks.data(), many.lsq.blocks.data(), one.lsq.blocks.size() * sizeof(PlaneFitBlock)),
              0);
    EXPECT_TRUE(sameBytes(one.dev.dev, many.dev.dev)) << threads << " threads: deviation table";
  }
}

TEST(TerrainThreads, ParallelRowsCoversEveryRowOnce) {
  ThreadsEnv env(7);
  std::vector<int> hits(1000, 0);
  parallelRows(
      1000,
      [&](int r0, int r1) {
        for (int r = r0; r < r1; ++r) ++hits[size_t(r)];
      },
      1);
  for (int h : hits) EXPECT_EQ(h, 1);
  EXPECT_THROW(parallelRows(
                   100, [](int, int) { throw std::runtime_error("band"); }, 1),
               std::runtime_error);
}

TEST(TerrainDetail, ResolutionDetailKeepsSmallTerrainsAndAddsOctavesToLargeOnes) {
  TerrainSpec fixed;
  fixed.size = 513;  // 512 / (1.5 * 2^8) < 2: "resolution" keeps the default 8 octaves
  TerrainSpec detail = fixed;
  detail.detailToSpacing = true;
  EXPECT_TRUE(sameBytes(makeProcedural(fixed).h, makeProcedural(detail).h));
  fixed.size = detail.size = 1025;  // one more octave fits: the heights differ
  const Heightfield a = makeProcedural(fixed), b = makeProcedural(detail);
  EXPECT_FALSE(sameBytes(a.h, b.h));
  EXPECT_EQ(b.minHeight, 0.0f);
  EXPECT_EQ(b.maxHeight, detail.heightScale);
}
