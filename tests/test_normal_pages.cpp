// The normal map in pages (render/normal_pages.h, terrain/normal_page_layout.h): storage only.
// NormalPageLayout.* check on the host that a bilinear read's four texels always lie in the page
// the shaders choose and that a page stores the level's texels (the edge repeated past it);
// NormalPagesGpu.* draw a terrain with its map in pages of 5 and 37 texels spread over several arrays
// and require the shaded images bit for bit equal to pages of 64, a planted defect (pages one texel
// off) to change them, and the one image the map fits (the sampler's filter) to shade within a level.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "config/config.h"
#include "error.h"
#include "gpu_fixture.h"
#include "render/normal_pages.h"
#include "render/renderer.h"
#include "schemes/registry.h"
#include "terrain/heightfield.h"
#include "terrain/normal_map.h"
#include "terrain/normal_page_layout.h"

using namespace lb;

namespace {

Heightfield terrain(int w, int h) {
  TerrainSpec s;
  s.size = std::max({w, h, 2});
  s.seed = 5;
  s.extent = 1000;
  s.heightScale = 160;
  Heightfield t = makeProcedural(s);
  Heightfield out = t;
  out.width = w, out.height = h;
  out.h.clear();
  for (int z = 0; z < h; ++z)
    out.h.insert(out.h.end(), t.h.begin() + ptrdiff_t(z) * t.width, t.h.begin() + ptrdiff_t(z) * t.width + w);
  out.updateRange();
  return out;
}

}  // namespace

TEST(NormalPageLayout, EveryBilinearReadLiesInOnePageThatStoresTheLevelsTexels) {
  for (const auto& [w, h] : std::vector<std::pair<int, int>>{{1, 1}, {2, 7}, {65, 65}, {100, 37}, {257, 193}}) {
    const Heightfield hf = terrain(w, h);
    const NormalMap nm = computeNormalMap(hf);
    for (int cells : {1, 3, 5, 64}) {
      const NormalPageLayout l = normalPageLayout(w, h, cells);
      ASSERT_EQ(int(l.levels.size()), nm.levels());
      std::vector<uint16_t> page(l.pageTexels() * 2);
      size_t wrong = 0, reads = 0;
      for (int k = 0; k < nm.levels(); ++k) {
        const NormalPageLevel& v = l.levels[size_t(k)];
        ASSERT_EQ(v.width, nm.levelWidth(k));
        ASSERT_EQ(v.height, nm.levelHeight(k));
        const auto& texels = nm.levelTexels(k);
        // Every clamped texel pair (a, a + 1) of both axes, as shaders/normals.glsl finds its page.
        for (int az = 0; az < v.height; ++az)
          for (int ax = 0; ax < v.width; ++ax) {
            const int bx = std::min(ax + 1, v.width - 1), bz = std::min(az + 1, v.height - 1);
            const int pi = std::min(ax / cells, v.pagesX - 1), pj = std::min(az / cells, v.pagesZ - 1);
            copyNormalPage(nm, l, v.first + pj * v.pagesX + pi, page.data());
            for (const auto& [x, z] : std::vector<std::pair<int, int>>{{ax, az}, {bx, az}, {ax, bz}, {bx, bz}}) {
              const int lx = x - pi * cells, lz = z - pj * cells;
              ++reads;
              if (lx < 0 || lz < 0 || lx > cells || lz > cells) {
                ++wrong;
                continue;
              }
              const size_t at = (size_t(lz) * size_t(cells + 1) + size_t(lx)) * 2,
                           want = (size_t(z) * size_t(v.width) + size_t(x)) * 2;
              wrong += page[at] != texels[want] || page[at + 1] != texels[want + 1];
            }
          }
      }
      EXPECT_EQ(wrong, 0u) << w << " x " << h << " in pages of " << cells << " (" << reads << " reads)";
    }
  }
}

TEST(NormalPageLayout, ChoosesThePageThatStoresLeastAndFitsTheArrays) {
  // A 1025^2 map: small pages waste least (a 1024-texel page would hold each coarse level alone).
  const NormalPageLayout small = normalPageLayout(1025, 1025);
  EXPECT_EQ(small.cells, 64);
  uint64_t texels = 0;
  for (const NormalPageLevel& v : small.levels) texels += uint64_t(v.width) * uint64_t(v.height);
  EXPECT_LT(uint64_t(small.pageCount()) * small.pageTexels(), texels * 11 / 10);
  // 65537^2 on an H100 (2048 layers, 4 GiB allocations): pages of 1024, 6 arrays of the 8 bound.
  const NormalPagesFit h100 = normalPagesFit(65537, 65537, 2048, 4ull << 30);
  EXPECT_EQ(h100.cells, 1024);
  EXPECT_LE(h100.arrays, 8u);
  EXPECT_GT(h100.bytes, 65537ull * 65537ull * 4);          // level 0 and the chain
  EXPECT_LT(h100.bytes, 65537ull * 65537ull * 4 * 3 / 2);  // little padding
  // Too few layers for any page size: the fit says so.
  EXPECT_GT(normalPagesFit(65537, 65537, 16, 4ull << 30).arrays, 8u);
}

class NormalPagesGpu : public lbtest::GpuTest {};

namespace {

// Small frames of uniform's default grid, for comparing shading pixel by pixel.
RenderSettings smallFrames() {
  RenderSettings s;
  s.width = 160;
  s.height = 90;
  s.grid = 8;
  return s;
}

// uniform's shaded frames at every pose, one after the other.
std::vector<uint8_t> shadedFrames(const Heightfield& hf, const RenderSettings& s,
                                  const std::vector<CameraPose>& poses) {
  Renderer r(lbtest::gpu(), hf, s);
  r.setScheme(*findScheme("uniform"), {});
  std::vector<uint8_t> out;
  for (const CameraPose& p : poses) {
    const std::vector<uint8_t> px = r.renderImage(p, p, RenderMode::Shaded);
    out.insert(out.end(), px.begin(), px.end());
  }
  return out;
}

}  // namespace

TEST_F(NormalPagesGpu, PagesOfAnySizeInSeveralArraysShadeAlike) {
  const Heightfield hf = terrain(257, 193);
  // Over the whole terrain, from far (coarse levels) and near (level 0 across page borders).
  const std::vector<CameraPose> poses = {lbtest::poseAt({-300, 700, -300}, {500, 0, 380}),
                                         lbtest::poseAt({310, 95, 240}, {620, 30, 520}, 50.0f)};
  const RenderSettings base = smallFrames();
  auto shaded = [&](const RenderSettings& s) { return shadedFrames(hf, s, poses); };
  RenderSettings paged64 = base;
  paged64.testNormalPageCells = 64;
  paged64.testNormalCoarseFrom = 99;  // every pixel from the pages: the next test has the coarse image
  const std::vector<uint8_t> want = shaded(paged64);
  for (int cells : {5, 37}) {
    RenderSettings s = base;
    s.testNormalPageCells = cells;
    s.testNormalCoarseFrom = 99;
    s.testNormalPageLayers = cells == 5 ? 512 : 16;  // several arrays, at most the 8 bound
    NormalPages pages = createNormalPages(lbtest::gpu(), computeNormalMap(hf), {}, cells, s.testNormalPageLayers);
    EXPECT_TRUE(pages.paged);
    EXPECT_GT(pages.arrays.size(), 1u) << cells;
    EXPECT_TRUE(shaded(s) == want) << "pages of " << cells << " texels shade differently";
    s.testNormalPageDefect = true;
    EXPECT_FALSE(shaded(s) == want) << "pages of " << cells << ": the planted defect went unseen";
  }
  // The one image the map fits, filtered by the sampler (8-bit weights where the pages' shader
  // filter has float ones): the same shading up to a level of 255.
  EXPECT_FALSE(createNormalPages(lbtest::gpu(), computeNormalMap(hf), {}).paged);
  const std::vector<uint8_t> single = shaded(base);
  ASSERT_EQ(single.size(), want.size());
  int worst = 0;
  for (size_t i = 0; i < single.size(); ++i) worst = std::max(worst, std::abs(int(single[i]) - int(want[i])));
  EXPECT_LE(worst, 1);
}

// A paged map's coarse levels are also one image: a pixel at or past its first level reads that
// image, a finer one the pages. A defect planted in the pages shows so: with the coarse image it
// changes some of the pixels it changes without it, never another, and not all of them.
TEST_F(NormalPagesGpu, APagedMapsCoarseLevelsShadeAsTheOneImage) {
  const Heightfield hf = terrain(257, 193);
  const std::vector<CameraPose> poses = {lbtest::poseAt({-300, 700, -300}, {500, 0, 380}),
                                         lbtest::poseAt({310, 95, 240}, {620, 30, 520}, 50.0f),
                                         lbtest::poseAt({40, 12, 60}, {200, 0, 160}, 50.0f)};
  auto shaded = [&](int coarseFrom, bool defect) {
    RenderSettings s = smallFrames();
    s.testNormalPageCells = 37;
    s.testNormalCoarseFrom = coarseFrom;
    s.testNormalPageDefect = defect;
    return shadedFrames(hf, s, poses);
  };
  const std::vector<uint8_t> clean = shaded(0, false), withCoarse = shaded(0, true), pagesOnly = shaded(99, true);
  ASSERT_EQ(withCoarse.size(), clean.size());
  ASSERT_EQ(pagesOnly.size(), clean.size());
  int changed = 0, changedPagesOnly = 0, outside = 0;
  for (size_t i = 0; i < clean.size(); i += 4) {
    const bool c = !std::equal(&withCoarse[i], &withCoarse[i] + 4, &clean[i]);
    const bool p = !std::equal(&pagesOnly[i], &pagesOnly[i] + 4, &clean[i]);
    changed += c;
    changedPagesOnly += p;
    outside += c && !p;
  }
  EXPECT_EQ(outside, 0) << "the coarse image changed pixels the pages' defect does not";
  EXPECT_GT(changed, 0) << "no pixel read the pages";
  EXPECT_LT(changed, changedPagesOnly) << "no pixel read the coarse image";
  std::printf("    pixels the planted defect changes: %d from the pages alone, %d with the coarse image\n",
              changedPagesOnly, changed);
  // Here the whole chain past level 0 fits one image: the coarse image starts at level 1.
  NormalPages p = createNormalPages(lbtest::gpu(), computeNormalMap(hf), {}, 37);
  EXPECT_EQ(p.coarseFrom, 1);
  EXPECT_EQ(p.image.mipLevels, uint32_t(computeNormalMap(hf).levels() - 1));
}

// The renderer takes pages by itself where one image cannot hold the map: a strip one sample
// longer than the device's largest image side.
TEST_F(NormalPagesGpu, AMapPastOneImageTakesPages) {
  NormalMap nm;
  nm.width = int(lbtest::gpu().props.limits.maxImageDimension2D) + 1;
  nm.height = 2;
  nm.texels.assign(size_t(nm.width) * 2 * 2, 0);
  for (int w = nm.width, h = nm.height; w > 1 || h > 1;) {
    w = std::max(1, w / 2), h = std::max(1, h / 2);
    nm.coarser.push_back({w, h, UninitVector<uint16_t>(size_t(w) * size_t(h) * 2, 0)});
  }
  const NormalPages pages = createNormalPages(lbtest::gpu(), nm, {});
  EXPECT_TRUE(pages.paged);
  EXPECT_GT(pages.layout.pageCount(), 1);
  EXPECT_FALSE(createNormalPages(lbtest::gpu(), computeNormalMap(terrain(65, 65)), {}).paged);
}

TEST_F(NormalPagesGpu, MoreArraysThanTheShadersBindAreRefused) {
  const NormalMap nm = computeNormalMap(terrain(65, 65));
  try {
    createNormalPages(lbtest::gpu(), nm, {}, 3, 1);  // 22 x 22 pages of level 0 alone, one layer an array
    FAIL() << "no refusal";
  } catch (const FeatureMissing& e) {
    EXPECT_NE(std::string(e.what()).find("page arrays"), std::string::npos) << e.what();
  }
}
