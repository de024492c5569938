// The terrain passes split rows across threads (terrain/parallel_rows.h): the thread count must
// change the time only, never a bit of the output. And "detail": "resolution" must leave sizes
// whose octave count stays 8 exactly as the default generator makes them.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <string>

#include "random.h"
#include "render/patch_grid.h"
#include "schemes/preprocess/density_map.h"
#include "schemes/preprocess/plane_fit.h"
#include "schemes/preprocess/tess_deviation.h"
#include "schemes/registry.h"
#include "terrain/heightfield.h"
#include "terrain/normal_map.h"
#include "terrain/parallel_rows.h"
#include "threads_env.h"

using namespace lb;

namespace {

template <typename Vector>
bool sameBytes(const Vector& a, const Vector& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
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

// Patch height bounds run patch rows in parallel on large terrains: every thread count gives what
// a plain scan of each patch's texels (widened by one) gives.
TEST(TerrainThreads, PatchHeightBoundsEqualAPlainScanOnAnyThreadCount) {
  Heightfield hf;
  hf.width = hf.height = 2049;  // 2049 x 8 rows a patch row at n = 256: bands of 63 rows, 4+ bands
  hf.extent = 1000;
  hf.h.resize(size_t(hf.width) * size_t(hf.height));
  SplitMix64 random{11};
  for (float& v : hf.h) v = float(random.below(100000)) * 0.01f;
  for (int n : {1, 7, 256})
    for (Topology topo : {Topology::Quad4, Topology::Tri3}) {
      std::vector<glm::vec2> plain;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const int x0 = i * 2048 / n, x1 = ((i + 1) * 2048 + n - 1) / n;
          const int z0 = j * 2048 / n, z1 = ((j + 1) * 2048 + n - 1) / n;
          glm::vec2 b(INFINITY, -INFINITY);
          for (int z = z0; z <= z1; ++z)
            for (int x = x0; x <= x1; ++x) b = glm::vec2(std::min(b.x, hf.at(x, z)), std::max(b.y, hf.at(x, z)));
          plain.push_back(b);
          if (topo == Topology::Tri3) plain.push_back(b);
        }
      for (int threads : {1, 3, 8}) {
        ThreadsEnv env(threads);
        EXPECT_TRUE(sameBytes(plain, patchHeightBounds(hf, n, topo))) << "n " << n << ", " << threads << " threads";
      }
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

// The generator evaluates 4 or 8 samples at a time; each lane must compute the one-at-a-time
// expressions exactly: the same bits for sides that are and are not multiples of 8, both
// detail modes, several seeds, and an extent far from the noise's lattice scale.
TEST(TerrainDetail, LaneGeneratorsAreTheOneSampleGeneratorBitForBit) {
  for (int size : {5, 258, 1027}) {
    for (bool detail : {false, true}) {
      for (uint32_t seed : {1u, 7u, 123456789u}) {
        TerrainSpec s;
        s.size = size;
        s.seed = seed;
        s.extent = size == 1027 ? 9.5e6f : 1000.0f;
        s.heightScale = 300;
        s.detailToSpacing = detail;
        const Heightfield one = makeProcedural(s, 1);
        EXPECT_GT(one.maxHeight, one.minHeight);
        for (int lanes : {4, 8})  // 8 runs the AVX2 lanes where the processor has them, else 4 again
          EXPECT_TRUE(sameBytes(makeProcedural(s, lanes).h, one.h))
              << size << " " << detail << " " << seed << " " << lanes;
      }
    }
  }
}
