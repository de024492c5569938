// Phong scheme: the Phong projection on the CPU against values worked out by hand; on the GPU,
// shape factor 0 renders exactly the flat triangles (against a flat evaluation shader), the corners
// never move, the LOD does not depend on alpha, edge factors follow the thesis' formula, neighbours
// agree on shared edges, and culling follows the thesis' frustum and back-face tests.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "camera/camera_matrices.h"
#include "gpu_fixture.h"
#include "render/patch_grid.h"
#include "schemes/preprocess/density_map.h"
#include "schemes/preprocess/phong_surface.h"

using namespace lb;

namespace {

// P0 at the origin, P1 and P2 two units along x and z; only n1 leans (45 degrees towards +x).
PhongTriangle leaningTriangle() {
  const float s = 1.0f / std::sqrt(2.0f);
  return {{{0, 0, 0}, {2, 0, 0}, {0, 0, 2}}, {{0, 1, 0}, {s, s, 0}, {0, 1, 0}}};
}

void expectNear(glm::vec3 got, glm::vec3 want, const char* what) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], 1e-6f) << what << " component " << k;
}

}  // namespace

TEST(PhongSurface, MatchesHandComputedPoints) {
  PhongTriangle t = leaningTriangle();
  // Centroid: p = (2/3, 0, 2/3). Projections onto the planes at P0 and P2 (normal +y) leave p alone;
  // onto the plane at P1: p - dot(p - P1, n1) n1 = p + (4 / (3 sqrt 2)) (1, 1, 0) / sqrt 2 = (4/3, 2/3, 2/3).
  // Mean of the three: (8/9, 2/9, 2/3).
  const glm::vec3 third(1.0f / 3.0f);
  expectNear(phongPoint(t, third), {8.0f / 9, 2.0f / 9, 2.0f / 3}, "centroid");
  expectNear(phongSurface(t, third, 0.5f), {7.0f / 9, 1.0f / 9, 2.0f / 3}, "centroid, alpha 0.5");
  // Midpoint of P0-P1: p = (1, 0, 0); the plane at P1 moves it to (1.5, 0.5, 0); mean (1.25, 0.25, 0).
  expectNear(phongPoint(t, {0.5f, 0.5f, 0}), {1.25f, 0.25f, 0}, "edge midpoint");
}

TEST(PhongSurface, CornersAndAlphaZeroAreExact) {
  PhongTriangle t = leaningTriangle();
  t.pos[1] = {2.1f, 0.3f, -0.2f};  // inexact coordinates: equality must still be bit-exact
  const glm::vec3 corners[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int k = 0; k < 3; ++k)
    for (float alpha : {0.0f, 0.3f, 0.75f, 1.0f}) {
      glm::vec3 p = phongSurface(t, corners[k], alpha);
      EXPECT_EQ(p, t.pos[k]) << "corner " << k << " alpha " << alpha;
    }
  const glm::vec3 b(0.2f, 0.3f, 0.5f);
  EXPECT_EQ(phongSurface(t, b, 0.0f), b.x * t.pos[0] + b.y * t.pos[1] + b.z * t.pos[2]);
}

TEST(PhongSurface, FaceNormalsGiveTheFlatTriangleAndEdgesIgnoreTheThirdCorner) {
  PhongTriangle t = leaningTriangle();
  for (auto& n : t.normal) n = {0, 1, 0};  // the triangle lies in y = 0
  expectNear(phongPoint(t, {0.2f, 0.3f, 0.5f}), {0.6f, 0.0f, 1.0f}, "planar");
  // On the edge P0-P1 (third coordinate 0) the curve depends on P0, P1 and their normals only,
  // which is why neighbouring triangles meet without cracks.
  PhongTriangle a = leaningTriangle(), b = leaningTriangle();
  b.pos[2] = {5, 3, -1};
  b.normal[2] = glm::normalize(glm::vec3(-1, 2, 3));
  EXPECT_EQ(phongSurface(a, {0.25f, 0.75f, 0}, 0.8f), phongSurface(b, {0.25f, 0.75f, 0}, 0.8f));
}

namespace {

// The phong scheme with the flat evaluation shader: same control shader, density map and parameters.
class FlatReference : public Scheme {
 public:
  explicit FlatReference(const Scheme& phong) : phong_(phong), info_(phong.info()) {
    info_.name = "phong-flat-reference";
    info_.tese = "terrain_tri_flat";
  }
  const SchemeInfo& info() const override { return info_; }
  float maxLevel(const ParamValues& v) const override { return phong_.maxLevel(v); }
  SampleMap sampleMap(const Heightfield& hf, const ParamValues& v) const override { return phong_.sampleMap(hf, v); }
  void update(FrameUniforms& f, const ParamValues& v) const override { phong_.update(f, v); }

 private:
  const Scheme& phong_;
  SchemeInfo info_;
};

struct Frame {
  std::vector<uint8_t> image;
  PipelineStats stats;
  std::vector<float> levels;
};

Frame render(Renderer& r, const Scheme& s, const ParamValues& params, const CameraPose& pose) {
  r.setScheme(s, params);
  FrameResult f;
  Frame out;
  out.image = r.renderImage(pose, pose, RenderMode::Shaded, &f);
  out.stats = f.stats;
  out.levels = r.capturedLevels();
  return out;
}

size_t differingPixels(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.size(); i += 4) n += std::memcmp(&a[i], &b[i], 4) != 0;
  return n;
}

void expectSameStats(const PipelineStats& a, const PipelineStats& b) {
  EXPECT_EQ(a.tcsPatches, b.tcsPatches);
  EXPECT_EQ(a.tesInvocations, b.tesInvocations);
  EXPECT_EQ(a.clipInvocations, b.clipInvocations);
}

constexpr int kGrid = 16;

}  // namespace

class PhongScheme : public lbtest::GpuTest {};

TEST_F(PhongScheme, AlphaZeroIsExactlyTheFlatTriangles) {
  const Scheme& phong = *findScheme("phong");
  FlatReference flat(phong);
  Renderer r(lbtest::gpu(), lbtest::testTerrain(), {160, 90, kGrid});
  auto pose = lbtest::poseAt({-100, 300, -100}, {500, 0, 500});
  ParamValues params{{"alpha", 0}, {"scale", 8}};
  Frame a = render(r, phong, params, pose), ref = render(r, flat, params, pose);
  expectSameStats(a.stats, ref.stats);
  EXPECT_EQ(a.stats.clipPrimitives, ref.stats.clipPrimitives);
  EXPECT_EQ(a.stats.fsInvocations, ref.stats.fsInvocations);
  EXPECT_EQ(a.levels, ref.levels);
  EXPECT_EQ(differingPixels(a.image, ref.image), 0u) << "alpha 0 must place every vertex on the flat triangle";
  // The LOD does not depend on alpha, but at alpha 1 the interior vertices leave the flat triangle.
  params["alpha"] = 1;
  Frame b = render(r, phong, params, pose);
  expectSameStats(b.stats, ref.stats);
  EXPECT_EQ(b.levels, ref.levels);
  EXPECT_GT(a.stats.tesInvocations, 3 * a.stats.tcsPatches) << "the view must tessellate to have interior vertices";
  EXPECT_GT(differingPixels(b.image, ref.image), b.image.size() / 4 / 20) << "Phong should move >5% of the pixels";
}

// With every factor 1 the tessellator emits only the three corners; Phong must leave them in place,
// so any alpha renders the same image as the flat triangles.
TEST_F(PhongScheme, CornersNeverMove) {
  const Scheme& phong = *findScheme("phong");
  FlatReference flat(phong);
  Renderer r(lbtest::gpu(), lbtest::testTerrain(), {160, 90, kGrid});
  auto pose = lbtest::poseAt({-100, 300, -100}, {500, 0, 500});
  // scale 0: density 1/255 everywhere, so no edge reaches factor 1 before the clamp.
  Frame ref = render(r, flat, {{"scale", 0}}, pose);
  int visible = 0;
  for (uint32_t p = 0; p < r.patchCount(); ++p) {
    const float* l = &ref.levels[size_t(p) * 8];
    if (l[4] == 0.0f) continue;
    ++visible;
    EXPECT_TRUE(l[0] == 1.0f && l[1] == 1.0f && l[2] == 1.0f && l[4] == 1.0f) << "patch " << p;
  }
  EXPECT_GT(visible, 100);
  EXPECT_EQ(ref.stats.tesInvocations, 3u * uint64_t(visible));
  for (float alpha : {0.5f, 1.0f}) {
    Frame a = render(r, phong, {{"scale", 0}, {"alpha", alpha}}, pose);
    expectSameStats(a.stats, ref.stats);
    EXPECT_EQ(differingPixels(a.image, ref.image), 0u) << "alpha " << alpha;
  }
}

// Edge factor = on-screen length of the edge / tri_size x max density along it; inner = mean of the
// unscaled edge factors x the largest edge density; each clamped to [1, 64] (thesis 5.2.4).
TEST_F(PhongScheme, FactorsAreScreenLengthTimesDensity) {
  const Heightfield& hf = lbtest::testTerrain();
  const float triSize = 2.0f, scale = 8.0f;
  Renderer r(lbtest::gpu(), hf, {160, 90, kGrid});
  auto pose = lbtest::poseAt({-100, 300, -100}, {500, 0, 500}, 45);
  Frame f = render(r, *findScheme("phong"), {{"tri_size", triSize}, {"scale", scale}}, pose);
  CameraMatrices cam = cameraMatrices(pose, 160.0f / 90.0f, hf.extent);
  auto map = densityMap(hf, 0.0f, scale);
  auto verts = gridVertices(kGrid, hf.extent);
  auto idx = patchIndices(kGrid, Topology::Tri3);
  int compared = 0, below64 = 0;
  for (uint32_t p = 0; p < r.patchCount(); ++p) {
    const float* l = &f.levels[size_t(p) * 8];
    if (l[4] == 0.0f) continue;
    glm::vec2 px[3];
    glm::ivec2 texel[3];
    bool front = true;
    for (int k = 0; k < 3; ++k) {
      uint32_t v = idx[p * 3 + uint32_t(k)];
      glm::vec2 xz = verts[v];
      glm::vec4 clip = cam.proj * (cam.view * glm::vec4(xz.x, hf.sample(xz.x, xz.y), xz.y, 1.0f));
      front = front && clip.w > 0;
      px[k] = glm::vec2(clip) / clip.w * 0.5f * glm::vec2(160, 90);
      int i = int(v % (kGrid + 1)), j = int(v / (kGrid + 1));
      texel[k] = {gridTexel(i, kGrid, hf.width), gridTexel(j, kGrid, hf.height)};
    }
    if (!front) continue;
    float screen[3], density[3];
    for (int k = 0; k < 3; ++k) {
      int a = (k + 1) % 3, b = (k + 2) % 3;
      screen[k] = glm::distance(px[a], px[b]) / triSize;
      density[k] = maxDensityAlongEdge(map, hf.width, texel[a], texel[b]);
      float want = std::clamp(screen[k] * density[k], 1.0f, 64.0f);
      EXPECT_NEAR(l[k], want, 1e-4f * want) << "patch " << p << " edge " << k;
      below64 += want > 1.0f && want < 64.0f;
    }
    float inner = (screen[0] + screen[1] + screen[2]) / 3.0f * std::max({density[0], density[1], density[2]});
    EXPECT_NEAR(l[4], std::clamp(inner, 1.0f, 64.0f), 1e-4f * std::clamp(inner, 1.0f, 64.0f)) << "patch " << p;
    ++compared;
  }
  EXPECT_GT(compared, 200);
  EXPECT_GT(below64, compared) << "most edges should be strictly between the clamps";
}

// Diagonal inside a quad, the vertical edge to the right neighbour, the horizontal edge below.
TEST_F(PhongScheme, SharedEdgesGetIdenticalLevels) {
  Renderer r(lbtest::gpu(), lbtest::testTerrain(), {160, 90, kGrid});
  auto pose = lbtest::poseAt({-100, 250, -100}, {500, 0, 500});
  Frame f = render(r, *findScheme("phong"), {{"scale", 8}}, pose);
  auto tri = [&](int i, int j, int t) { return &f.levels[size_t(2 * (j * kGrid + i) + t) * 8]; };
  int compared = 0;
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      const float *t0 = tri(i, j, 0), *t1 = tri(i, j, 1);
      auto same = [&](const float* a, int ea, const float* b, int eb) {
        if (a[4] == 0 || b[4] == 0) return;  // a culled side draws nothing along the edge
        EXPECT_EQ(a[ea], b[eb]) << "quad " << i << "," << j;
        ++compared;
      };
      same(t0, 1, t1, 2);                                   // 00-11: opposite 10 in t0, opposite 01 in t1
      if (i + 1 < kGrid) same(t0, 0, tri(i + 1, j, 1), 1);  // 10-11 = the neighbour's 00-01
      if (j + 1 < kGrid) same(t1, 0, tri(i, j + 1, 0), 2);  // 11-01 = the neighbour's 00-10
    }
  EXPECT_GT(compared, 300);
}

// Each triangle is culled exactly when (thesis 5.2.4) all corners lie more than the margin beyond one
// frustum plane, or all three edge normals (mean of the end points' grid normals) point away from
// the eye with dot <= -tolerance. Recomputed on the CPU; decisions within 1e-4 of a threshold are skipped.
TEST_F(PhongScheme, CullingFollowsTheThesisTests) {
  const Heightfield& hf = lbtest::testTerrain();
  Renderer r(lbtest::gpu(), hf, {160, 90, kGrid});
  auto pose = lbtest::poseAt({-50, 60, 500}, {1050, 20, 500});  // low and level: back faces behind hills
  CameraMatrices cam = cameraMatrices(pose, 160.0f / 90.0f, hf.extent);
  glm::vec4 planes[6];
  frustumPlanes(cam.proj * cam.view, planes);
  auto verts = gridVertices(kGrid, hf.extent);
  auto idx = patchIndices(kGrid, Topology::Tri3);
  const float d = hf.extent / kGrid;  // phong.tesc gridNormal(): central differences one cell apart
  auto normal = [&](glm::vec2 xz) {
    float hl = hf.sample(xz.x - d, xz.y), hr = hf.sample(xz.x + d, xz.y);
    float hd = hf.sample(xz.x, xz.y - d), hu = hf.sample(xz.x, xz.y + d);
    return glm::normalize(glm::vec3((hl - hr) / (2 * d), 1, (hd - hu) / (2 * d)));
  };
  for (float tolerance : {0.0f, 0.25f}) {
    const float frustumTolerance = 0.1f;
    Frame f = render(r, *findScheme("phong"),
                     {{"backface_tolerance", tolerance}, {"frustum_tolerance", frustumTolerance}}, pose);
    int checked = 0, backFaces = 0, outside = 0;
    for (uint32_t p = 0; p < r.patchCount(); ++p) {
      glm::vec3 pos[3], n[3];
      for (int k = 0; k < 3; ++k) {
        glm::vec2 xz = verts[idx[p * 3 + uint32_t(k)]];
        pos[k] = {xz.x, hf.sample(xz.x, xz.y), xz.y};
        n[k] = normal(xz);
      }
      float longest =
          std::max({glm::distance(pos[0], pos[1]), glm::distance(pos[1], pos[2]), glm::distance(pos[2], pos[0])});
      float margin = frustumTolerance * longest, closest = 1e9f;
      bool isOutside = false, isBack = true;
      for (int i = 0; i < 5; ++i) {
        float worst = -1e9f;  // the corner least beyond the plane
        for (int k = 0; k < 3; ++k)
          worst = std::max(worst, glm::dot(glm::vec3(planes[i]), pos[k]) + planes[i].w + margin);
        isOutside = isOutside || worst <= 0;
        closest = std::min(closest, std::abs(worst));
      }
      for (int k = 0; k < 3; ++k) {
        int a = (k + 1) % 3, b = (k + 2) % 3;
        float dot = glm::dot(glm::normalize(n[a] + n[b]), glm::normalize(cam.eye - 0.5f * (pos[a] + pos[b])));
        isBack = isBack && dot <= -tolerance;
        closest = std::min(closest, std::abs(dot + tolerance));
      }
      if (closest < 1e-4f) continue;
      EXPECT_EQ(f.levels[size_t(p) * 8 + 4] == 0.0f, isOutside || isBack)
          << "triangle " << p << " tolerance " << tolerance;
      ++checked;
      outside += isOutside;
      backFaces += isBack && !isOutside;
    }
    EXPECT_GT(checked, int(r.patchCount()) - 5);
    EXPECT_GT(outside, 0) << "tolerance " << tolerance;
    EXPECT_GT(backFaces, 0) << "tolerance " << tolerance;
  }
  // Everything is culled when the camera looks away from the terrain.
  Frame away = render(r, *findScheme("phong"), {}, lbtest::poseAt({500, 400, 500}, {500, 2000, 3000}));
  for (uint32_t p = 0; p < r.patchCount(); ++p) EXPECT_EQ(away.levels[size_t(p) * 8 + 4], 0.0f);
  EXPECT_EQ(away.stats.tesInvocations, 0u);
}
