// Concurrent binary tree (Dupuy, "Concurrent Binary Trees (with application to longest edge
// bisection)", HPG 2020; the LEB2D terrain demo; Benyoub & Dupuy, "Concurrent Binary Trees for
// Large-Scale Game Components", HPG 2024): longest-edge bisection of the terrain square kept on the
// GPU and refined a little every frame. Drawn through the GPU-indirect path: four compute passes
// (shaders/cbt_*.comp) update the tree and write one instanced indirect draw of a leaf mesh.
//
// Tree. Node 1 is the square, nodes 2 and 3 its halves along the diagonal, node k's children 2k and
// 2k + 1 the halves of its hypotenuse. The state holds a bitfield over the 2^D nodes of depth D, one
// set bit per leaf (at its leftmost descendant), its copy as of the last reduction (what the next
// update reads while it changes the bitfield), and the sum reduction of every level down to one
// 32-bit word a node (shaders/cbt_params.h): a node is split exactly when its subtree holds two or
// more bits, so leaf i is found by an O(D) walk from the root (shaders/cbt.glsl cbtLeaf). Splitting a
// node sets one bit and merging clears one: concurrent updates need only atomicOr and atomicAnd.
//
// Depth. The square is 2^L lattice units a side, L = ceil(log2(S)) for S = (samples - 1) *
// cells_per_texel along the longer axis (at least s + 2), and D = 2 (L - s) + 1, so the deepest
// leaf's micro-triangles have legs of one lattice unit: no finer than the heightfield asks for
// (the note's D = 13 for 513^2, 23 for 16385^2 at s = 3). Every corner down to depth D, micro-
// vertices included, is then an integer, and shared vertices are bit-identical.
//
// Rule (LEB2D, terrain.cpp computeLodFactor and TerrainRenderCommon.glsl). LoD = 2 + 2 log2(px / t),
// px the leaf's hypotenuse |e| projected at its midpoint m, |e| K / (|m| 2^s) with K the pixels per
// unit at distance 1: the micro-triangle's hypotenuse in pixels. Split when LoD > 1 (px > t / sqrt 2),
// merge a diamond when neither parent would split, so at rest micro-hypotenuses are t/2 ... t/sqrt 2
// pixels, areas t^2/16 ... t^2/8: targetAreaPx = t^2 / (8 sqrt 2) is the middle of that octave. Split
// on even updates (conforming: the node across the hypotenuse splits too, and its parent first when
// it is coarser), merge on odd ones, so the detail moves by at most a level a frame. Leaves outside
// the culling frustum (box: the leaf's triangle in x, z and the terrain's height range) neither
// split nor keep their parents split; as in LEB2D they are still drawn. Left out: the demo's
// flatness test, whose threshold is in world units.
//
// Pool. The renderer holds C = min(pool, 2^D, the device's most) instance records, one a leaf: a
// tree of depth D never has more than 2^D leaves, and the pool is the view budget's. At rest a
// leaf's micro-hypotenuses project to at least t/2 px, its micro-triangles to t^2/16 px^2 or more
// seen face on, so a W x H viewport shows at most 16 W H / (4^s t^2) leaves face on; foreshortened
// ground, the frustum's border and a frame's lag of merges add more. The pool is 4 times that,
// rounded up to a power of two, at least 2^17. Source: large_cbt (Benyoub & Dupuy 2024) keeps a
// fixed pool of 128K (its default), 256K, 512K or 1M bisectors (demo/include/cbt/ocbt_*.h), each
// drawn as one triangle of about T = 60 px^2: 128K x 60 px^2 is 3.8 screens of 1920 x 1080, the 4
// here. A bisector is a leaf of 4^s triangles here, and at 1920 x 1080, subd 3 the rule gives the
// source's four pools from t >= 4, 2.8, 2.0 and 1.4 px: 128K at the default t = 7, 2^23 (8M, 256
// MiB of records) at t = 0.5, the parameter's least; larger viewports get more, past the source's
// 1M. The device's most: maxStorageBufferRange and maxMemoryAllocationSize over 32 bytes a record,
// and maxComputeWorkGroupCount[0] x 64 leaves a dispatch; a pool they cut is recorded
// (cbt_capacity_clamped). Leaves past C are neither updated nor drawn: the batch pass counts them
// as overflow and the case fails ("LOD state overflow"; a matched search records the trial and goes
// on). `pool` > 0 replaces the rule (a sweep over the source's four, say); cbt_pool records the one
// asked for.
//
// Depth limit. kMaxDepth = 27 keeps the state (2^(D - 1) bytes) within 64 MiB; the H100's largest
// terrain, 32759^2, is L = 16 at cells_per_texel 2 and fits at subd 3 or more (D = 27). A deeper
// tree is an InputError that names the least subd and the most cells_per_texel that fit.
//
// Parameters: tri_size t = 7 px and subd s = 3 (64 triangles a leaf) are LEB2D's defaults.
#include "schemes/cbt.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "error.h"
#include "number_text.h"
#include "shaders/cbt_params.h"
#include "terrain/heightfield.h"

namespace lb {
namespace {

constexpr uint32_t kMaxDepth = 27;                // 16 MiB of bits, 16 MiB of their copy, 32 MiB of sums
constexpr uint64_t kMinPool = uint64_t(1) << 17;  // large_cbt's smallest and default pool, 128K bisectors
constexpr double kPoolHeadroom = 4;               // the source's 128K x 60 px^2 over a 1920 x 1080 screen: 3.8

uint32_t floatBits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

// The leaf mesh: a right triangle cut 2^s times along each leg, vertices (u, v) with u + v <= 2^s,
// u towards corner a and v towards c. Wound so that the histogram pass sees the terrain's upper
// side as front-facing, as the tessellated and instanced grids (the test compares their
// back-facing shares from above).
Footprint leafMesh(int s) {
  const int n = 1 << s;
  Footprint f;
  f.name = "leaf";
  std::vector<std::vector<uint32_t>> at(size_t(n + 1));
  for (int v = 0; v <= n; ++v)
    for (int u = 0; u + v <= n; ++u) {
      at[size_t(u)].push_back(uint32_t(f.vertices.size()));
      f.vertices.emplace_back(float(u), float(v));
    }
  auto idx = [&](int u, int v) { return at[size_t(u)][size_t(v)]; };
  for (int v = 0; v < n; ++v)
    for (int u = 0; u + v < n; ++u) {
      f.indices.insert(f.indices.end(), {idx(u, v), idx(u + 1, v), idx(u, v + 1)});
      if (u + v + 2 <= n) f.indices.insert(f.indices.end(), {idx(u + 1, v), idx(u + 1, v + 1), idx(u, v + 1)});
    }
  return f;
}

}  // namespace

uint64_t cbtViewPool(const GpuLodBudget& budget, const ParamValues& v) {
  if (budget.viewportWidth == 0 || budget.viewportHeight == 0)
    throw std::logic_error("cbt: the view budget names no viewport");
  const double t = v.at("tri_size"), faceOn = std::ldexp(1.0, 2 * int(v.at("subd"))) * t * t / 16.0;
  const double leaves = kPoolHeadroom * double(budget.viewportWidth) * double(budget.viewportHeight) / faceOn;
  uint64_t pool = kMinPool;
  while (double(pool) < leaves && pool < (uint64_t(1) << 31)) pool *= 2;
  return pool;
}

GpuLod cbtTree(const Heightfield& hf, const ParamValues& v, const GpuLodBudget& budget, uint32_t perDraw) {
  const int s = int(v.at("subd"));
  const double cells = double(std::max(hf.width, hf.height) - 1) * v.at("cells_per_texel");
  const uint32_t L = std::max(uint32_t(std::ceil(std::log2(std::max(cells, 1.0)) - 1e-9)), uint32_t(s) + 2);
  const uint32_t D = 2 * (L - uint32_t(s)) + 1;
  if (D > kMaxDepth) {
    // D <= kMaxDepth while L <= (kMaxDepth - 1) / 2 + s: the least subd, and the most cells a side.
    const uint32_t maxL = (kMaxDepth - 1) / 2 + uint32_t(s);
    const int leastSubd = int(L) - int((kMaxDepth - 1) / 2);
    const std::string most =
        numberText(std::floor(std::ldexp(1000.0, int(maxL)) / double(std::max(hf.width, hf.height) - 1)) / 1000.0);
    throw InputError("cbt: a tree of depth " + std::to_string(D) + " (2^" + std::to_string(L) +
                     " lattice units a side: " + std::to_string(std::max(hf.width, hf.height) - 1) +
                     " sample spacings x cells_per_texel " + numberText(v.at("cells_per_texel")) + ", subd " +
                     std::to_string(s) + ") exceeds depth " + std::to_string(kMaxDepth) +
                     ", the deepest state cbt keeps (64 MiB); " +
                     (leastSubd <= 5 ? "raise subd to " + std::to_string(leastSubd) + " or " : std::string()) +
                     "lower cells_per_texel to " + most + " or less");
  }
  GpuLod g;
  g.footprint = leafMesh(s);
  const uint32_t words = 1u << (D - 5), sums = LB_CBT_HEADER + 2 * words;
  std::vector<uint32_t>& st = g.initialState;
  st.assign(size_t(sums) + (size_t(1) << (D - 4)), 0u);
  const uint32_t leaves = 2;
  // The pool rule (the head comment): the parameter or the view budget's, within the tree's 2^D
  // leaves and the device's most.
  const uint64_t pool = v.at("pool") > 0 ? uint64_t(v.at("pool")) : cbtViewPool(budget, v);
  const uint64_t wanted = std::min(pool, uint64_t(1) << D);
  const uint64_t deviceMost =
      std::min(budget.maxRecordBytes / sizeof(InstanceRecord), uint64_t(budget.maxDispatchGroups) * LB_CBT_GROUP);
  g.maxInstances = uint32_t(std::min({wanted, deviceMost, uint64_t(UINT32_MAX)}));
  st[LB_CBT_DEPTH] = D;
  st[LB_CBT_LATTICE_LOG2] = L;
  st[LB_CBT_CAPACITY] = g.maxInstances;
  st[LB_CBT_DISPATCH] = 1, st[LB_CBT_DISPATCH + 1] = 1, st[LB_CBT_DISPATCH + 2] = 1;
  st[LB_CBT_LEAVES] = leaves;
  st[LB_CBT_MIN_HEIGHT] = floatBits(hf.minHeight);
  st[LB_CBT_MAX_HEIGHT] = floatBits(hf.maxHeight);
  st[LB_CBT_INDEX_COUNT] = uint32_t(g.footprint.indices.size());
  // The two root triangles' bits (nodes 2 and 3, at their leftmost descendants) and their sums.
  const uint64_t bits[2] = {0, uint64_t(1) << (D - 1)};
  for (uint64_t b : bits) {
    st[LB_CBT_HEADER + b / 32] |= 1u << (b % 32);
    st[LB_CBT_HEADER + words + b / 32] |= 1u << (b % 32);
    for (uint32_t l = 0; l + 5 <= D; ++l) st[sums + (1u << l) + uint32_t(b >> (D - l))] += 1;
  }
  g.passes.push_back({.shader = "cbt_update", .indirectWord = LB_CBT_DISPATCH});
  for (int start = int(D) - 5;; start -= 6) {
    g.passes.push_back({.shader = "cbt_reduce", .groups = ((1u << start) + 31) / 32, .spec = start});
    if (start <= 5) break;
  }
  g.passes.push_back({.shader = "cbt_batch", .groups = 1, .spec = perDraw});
  g.maxDraws = perDraw == 0 ? 1 : (g.maxInstances + perDraw - 1) / perDraw;
  g.passes.push_back({.shader = "cbt_records", .indirectWord = LB_CBT_DISPATCH});
  g.convergeLimit = 2 * D + 8;
  g.overflowWord = LB_CBT_OVERFLOW;
  g.capacityWord = LB_CBT_CAPACITY;
  g.treeFirstWord = LB_CBT_HEADER, g.treeWordCount = words;  // the leaf bitfield: the tree
  g.facts = {{"cbt_depth", double(D)},
             {"cbt_lattice_log2", double(L)},
             {"cbt_state_bytes", double(st.size() * sizeof(uint32_t))},
             {"cbt_pool", double(pool)},
             {"cbt_capacity", double(g.maxInstances)},
             {"cbt_capacity_clamped", g.maxInstances < wanted ? 1.0 : 0.0}};
  return g;
}

const std::vector<ParamSpec>& cbtParams() {
  static const std::vector<ParamSpec> kParams = {
      {"tri_size", LB_CBT_TRI_SIZE, 7, 0.5, 64, false,
       "target micro-triangle hypotenuse in pixels: split while it projects over tri_size / sqrt 2"},
      {"subd", LB_CBT_SUBD, 3, 0, 5, true, "each leaf is drawn as 4^subd triangles"},
      {"cells_per_texel", LB_CBT_CELLS_PER_TEXEL, 1, 0.25, 16, false,
       "finest micro-triangle legs per heightfield sample spacing (sets the tree's depth)"},
      {"cull", LB_CBT_CULL, 1, 0, 1, true, "1 = leaves outside the frustum merge and never split"},
      {"pool", LB_CBT_POOL, 0, 0, double(uint64_t(1) << kMaxDepth), true,
       "leaf records the renderer holds (large_cbt's bisector pool: 131072 ... 1048576); 0 = from the view "
       "budget, 4 x viewport px / (4^subd tri_size^2 / 16), within 2^depth and the device's limits"}};
  return kParams;
}

double cbtTargetAreaPx(const ParamValues& v) {
  const double t = v.at("tri_size");
  return t * t / (8.0 * std::sqrt(2.0));
}

namespace {

class Cbt : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = {
        .name = "cbt",
        .description =
            "concurrent binary tree: longest-edge bisection refined on the GPU every frame, leaves instanced",
        .seed = "Dupuy 2020, Concurrent Binary Trees; LEB2D demo; Benyoub & Dupuy 2024 (large_cbt)",
        .params = cbtParams(),
        .mainParam = "tri_size",
        .mainParamRole = MainParamRole::TriangleWidthPx,
        .front = {4, 7, 14},
        .path = DrawPath::GpuIndirect,
        .vert = "cbt",
    };
    return kInfo;
  }

  double targetAreaPx(const ParamValues& v) const override { return cbtTargetAreaPx(v); }

  GpuLod gpuLod(const Heightfield& hf, const ParamValues& v, const GpuLodBudget& budget) const override {
    return cbtTree(hf, v, budget, 0);
  }
};

}  // namespace

const Scheme& cbtScheme() {
  static const Cbt scheme;
  return scheme;
}

}  // namespace lb
