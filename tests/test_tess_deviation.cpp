// errbound's deviation table (schemes/preprocess/tess_deviation.h): the fast table skips every edge and
// triangle whose bound (schemes/preprocess/deviation_bounds.h) cannot raise its level's maximum, and must be
// the oracle's table bit for bit on every kind of terrain and patch layout; and the bounds must
// bound what the exact code computes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "dem_crop.h"
#include "schemes/preprocess/deviation_bounds.h"
#include "schemes/preprocess/tess_deviation.h"
#include "terrain/generators.h"
#include "terrain/heightfield.h"

using namespace lb;

namespace {

Heightfield field(int width, int height, float base, float amplitude, unsigned seed) {
  Heightfield hf;
  hf.width = width;
  hf.height = height;
  hf.extent = 100;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-amplitude, amplitude);
  for (int i = 0; i < width * height; ++i) hf.h.push_back(base + u(rng));
  hf.updateRange();
  return hf;
}

Heightfield procedural(int size, bool detail, float heightScale = 1500) {
  TerrainSpec spec;
  spec.size = size;
  spec.seed = 3;
  spec.detailToSpacing = detail;
  spec.extent = float(size - 1);  // 1 m spacing: the large-terrain runs' relief per texel
  spec.heightScale = heightScale;
  return makeHeightfield(spec);
}

// The bounded table (at every patch size, not only where tessDeviation picks it) and the
// oracle's, compared bit for bit (floats, not values: -0 and NaN would show).
void expectSameTable(const Heightfield& hf, int grid, const std::string& what) {
  const DeviationTable fast = tessDeviationBounded(hf, grid), oracle = tessDeviationReference(hf, grid);
  ASSERT_EQ(fast.grid, grid) << what;
  ASSERT_EQ(fast.dev.size(), oracle.dev.size()) << what;
  for (size_t i = 0; i < fast.dev.size(); ++i)
    if (std::memcmp(&fast.dev[i], &oracle.dev[i], sizeof(float)) != 0) {
      ADD_FAILURE() << what << " grid " << grid << ": patch " << i / kErrboundLevels << " level " << i % kErrboundLevels
                    << ": fast " << fast.dev[i] << ", oracle " << oracle.dev[i];
      return;
    }
}

// The bilinear height the table uses at texel coordinates p (cell clamped to the border).
double bilinear(const Heightfield& hf, glm::dvec2 p) {
  const int x = std::clamp(int(std::floor(p.x)), 0, hf.width - 2),
            z = std::clamp(int(std::floor(p.y)), 0, hf.height - 2);
  const double fx = p.x - x, fz = p.y - z;
  const double h00 = hf.at(x, z), h10 = hf.at(x + 1, z), h01 = hf.at(x, z + 1), h11 = hf.at(x + 1, z + 1);
  return h00 + (h10 - h00) * fx + (h01 - h00) * fz + (h00 - h10 - h01 + h11) * fx * fz;
}

}  // namespace

TEST(TessDeviationFast, MatchesTheOracleOnProceduralTerrains) {
  // Patches of 256 texels as at grid 64 on 16385^2 (fine relief and the default 8 octaves), and
  // coarser and finer grids over the same heights.
  const Heightfield detail = procedural(513, true), smooth = procedural(257, false);
  for (int grid : {1, 2, 3, 8}) expectSameTable(detail, grid, "detail 513");
  for (int grid : {1, 4, 16}) expectSameTable(smooth, grid, "smooth 257");
}

TEST(TessDeviationFast, PicksTheBoundsFromPatchesOf32Texels) {
  // Either choice gives the oracle's bits; what is checked here is that both sides of the
  // threshold run and agree.
  const Heightfield hf = procedural(257, true);
  for (int grid : {8, 9}) {  // 32 and 28.4 texels a side
    const DeviationTable picked = tessDeviation(hf, grid), oracle = tessDeviationReference(hf, grid);
    EXPECT_EQ(std::memcmp(picked.dev.data(), oracle.dev.data(), picked.dev.size() * sizeof(float)), 0) << grid;
  }
}

TEST(TessDeviationFast, MatchesTheOracleOnFlatAndConstantGround) {
  TerrainSpec spec;
  spec.size = 129;
  const Heightfield flat = makeFlat(spec);
  for (int grid : {1, 4, 16}) expectSameTable(flat, grid, "flat");
  const Heightfield level = field(65, 65, 1000.0f, 0.0f, 1);  // constant, far from 0
  for (int grid : {1, 4}) expectSameTable(level, grid, "constant 1000");
  const DeviationTable t = tessDeviationBounded(flat, 4);
  for (float d : t.dev) EXPECT_EQ(d, std::nextafter(0.0f, 1.0f));  // exactly 0, rounded up
}

TEST(TessDeviationFast, MatchesTheOracleOnSpikes) {
  TerrainSpec spec;
  spec.size = 257;
  spec.seed = 7;
  spec.heightScale = 500;
  const Heightfield spikes = makeSpikes(spec);
  for (int grid : {1, 4, 8}) expectSameTable(spikes, grid, "spikes");
  // Planted one-sample spikes (up and down) on a gentle ramp: on patch borders and corners, on
  // the terrain's last row and column, and between samples of the level-64 grid.
  Heightfield ramp = field(129, 129, 0.0f, 0.01f, 2);
  for (int z = 0; z < 129; ++z)
    for (int x = 0; x < 129; ++x) ramp.h[size_t(z * 129 + x)] += 0.3f * x - 0.2f * z;
  const int planted[][3] = {{64, 64, 1},  {32, 0, -1},   {128, 77, 1}, {5, 128, 1},
                            {33, 61, -1}, {128, 128, 1}, {0, 0, -1}};
  for (const auto& s : planted) ramp.h[size_t(s[1] * 129 + s[0])] += 5000.0f * s[2];
  for (int grid : {1, 2, 4, 8}) expectSameTable(ramp, grid, "planted spikes");
}

TEST(TessDeviationFast, MatchesTheOracleWhenPatchesAreNotWholeTexels) {
  // (size - 1) / grid not an integer: patch corners and every level's vertices fall between
  // samples, and blocks and patches do not line up.
  const Heightfield rough = field(97, 97, 0.0f, 50.0f, 4);
  for (int grid : {5, 7, 3}) expectSameTable(rough, grid, "97 rough");
  const Heightfield wide = field(101, 61, -300.0f, 20.0f, 5);  // not square, negative heights
  for (int grid : {3, 6}) expectSameTable(wide, grid, "101 x 61");
  // Far texel coordinates (x up to 2048) on a thin strip, and heights far from 0.
  Heightfield strip = field(2049, 9, 8000.0f, 3.0f, 6);
  for (int grid : {8, 3}) expectSameTable(strip, grid, "2049 x 9");
}

TEST(TessDeviationFast, MatchesTheOracleOnTinyTerrains) {
  // More patches than cells: patches a fraction of a texel wide (width 1 is below the contract;
  // the fast table hands it to the oracle).
  for (int w : {1, 2, 3, 5})
    for (int h : {2, 4})
      for (int grid : {1, 3})
        expectSameTable(field(w, h, 10.0f, 5.0f, unsigned(w * 10 + h)), grid,
                        std::to_string(w) + "x" + std::to_string(h));
}

TEST(TessDeviationFast, MatchesTheOracleWhenHeightsAreNotFinite) {
  // The loaders refuse such heights; if one got through, the table still must not depend on
  // which items were skipped.
  Heightfield hf = field(33, 33, 0.0f, 10.0f, 11);
  hf.h[size_t(5 * 33 + 7)] = NAN;
  hf.h[size_t(20 * 33 + 30)] = INFINITY;
  for (int grid : {1, 3, 4}) expectSameTable(hf, grid, "NaN and infinity");
}

TEST(TessDeviationFast, MatchesTheOracleOnTheRealDem) {
  const Heightfield dem = makeHeightfield(lbtest::demCrop());
  for (int grid : {8, 5}) expectSameTable(dem, grid, "N44W072 crop");
}

TEST(TessDeviationFast, BoundsHoldOverRandomTriangles) {
  // Each bound must be >= the exact value (what triangleDeviation computes from the same
  // heights): random triangles of every size, on rough and on smooth steep ground.
  for (const Heightfield& hf : {field(65, 65, 100.0f, 40.0f, 8), procedural(129, false)}) {
    for (int fine : {1, 2, 4}) {
      DeviationBounds bounds;
      bounds.build(hf, 0, 0, hf.width - 1, hf.height - 1, fine);
      std::mt19937 rng(9);
      std::uniform_real_distribution<double> u(0, hf.width - 1);
      for (int t = 0; t < 400; ++t) {
        const double size = t < 100 ? 4 : t < 200 ? 16 : hf.width - 1;
        std::uniform_real_distribution<double> near(-size / 2, size / 2);
        const glm::dvec2 a(u(rng), u(rng));
        auto around = [&] {
          return glm::dvec2(std::clamp(a.x + near(rng), 0.0, hf.width - 1.0),
                            std::clamp(a.y + near(rng), 0.0, hf.height - 1.0));
        };
        glm::dvec2 b = around(), c = around();
        if (t % 7 == 0) b.y = a.y;  // axis-parallel edges too
        const double ha = bilinear(hf, a), hb = bilinear(hf, b), hc = bilinear(hf, c);
        const double exact = triangleDeviation(hf, a, b, c);
        const double box = std::max({bounds.edge(a, b, ha, hb), bounds.edge(b, c, hb, hc), bounds.edge(c, a, hc, ha),
                                     bounds.triangle(a, b, c, ha, hb, hc)});
        const double along = std::max({bounds.edgeAlong(a, b, ha, hb), bounds.edgeAlong(b, c, hb, hc),
                                       bounds.edgeAlong(c, a, hc, ha), bounds.triangle(a, b, c, ha, hb, hc)});
        EXPECT_GE(box, exact) << "fine " << fine << " triangle " << t;
        EXPECT_GE(along, exact) << "fine " << fine << " triangle " << t;
      }
    }
  }
}
