// Geometry clipmaps (Losasso & Hoppe 2004; Asirvatham & Hoppe, GPU Gems 2 ch. 2) on a resident
// heightfield: no compression, synthesis or toroidal texture update, only the nested grids, their
// footprints and the transition blend. Drawn through the instanced-grid path: the CPU places the
// footprints every frame (select), shaders/clipmap.vert blends heights.
//
// Levels. Level l has spacing g_l = 2^l finest lattice cells and n = 4m - 1 vertices a side
// (m = `block`, the paper's m = (n + 1) / 4). Its square starts at O_l = 2 g_l floor(v / 2 g_l) -
// (2m - 2) g_l along each axis, v the LOD eye in lattice units: every vertex is a multiple of g_l
// (x / g_l integral, nothing swims), O_l is a multiple of 2 g_l (so the square's border falls on
// the coarser level's vertices), and O_l - O_{l+1} is (2m - 2) g_l or 2m g_l for every v, so level
// l always fits the 2m-cell hole of level l + 1 with one coarse cell left over: the L-shaped trim,
// on the low or high side of each axis. The eye lies within g_l of the square's centre.
//
// Footprints (level cells, scaled by g_l from the record): the block of m x m vertices, the m x 3
// fix-ups along x and along z, the trim as two bars (2m x 1 and 1 x (2m - 1) cells: two footprints
// whose placement says the orientation, instead of four L meshes), the 2 x 2-cell centre, and the
// degenerate strip in pieces along x and along z. A ring is 12 blocks + 4 fix-ups + the two trim
// bars; the finest active level is a full square: 16 blocks + 8 fix-ups + the centre. Every cell is
// split along the same diagonal, (0,0)-(1,1), counter-clockwise in (x, z) like the tessellated
// grids, so every triangle faces up and a fine cell's diagonal continues its coarse cell's.
//
// Cracks. A level's border vertices on odd coordinates sit halfway along a coarse edge (a
// T-junction). The blend makes them exactly the mean of that edge's ends, so the surface is closed
// in exact arithmetic; the strip (v_2k, v_2k+1, v_2k+2) along each level's border, drawn with the
// finer level's record, makes it closed in floats too: every edge on the border then occurs twice,
// with bit-equal ends, since both levels compute the even vertices as terrainHeight of the same
// lattice point (the coarse level's blend is 0 on its hole's border, the fine level's is 1 on its
// own border). `strip` = 0 drops it: the negative control, T-junction cracks. The strip is cut
// where the coarse instances beside it meet (m - 1, m - 2 or 2 coarse cells; the 2m - 1 beside a
// trim bar as all three) and each piece is drawn exactly when its coarse instance is: culling then
// never leaves a coarse edge or a strip triangle's halves open beside each other, which the
// analytic crack check would count as a T-junction although nothing there is on screen.
//
// Transition (paper 2.3.5). w = floor(n / 10); alpha_x = clamp((|x - v_x| / g_l - ((n - 1) / 2 -
// w - 1)) / w, 0, 1), alpha = max(alpha_x, alpha_z), v the viewer as in the paper, not the snapped
// centre. Both give alpha = 1 on the border: the viewer is within g_l of the centre, which is what
// the paper's "- 1" allows for (|x - v| / g_l >= 2m - 2 on every border vertex, so the argument is
// >= w). The viewer keeps alpha continuous in time; the snapped centre would jump by 2 g_l when the
// level moves, and the blend with it. The coarsest drawn level has no coarser one: w = 0, no blend.
//
// Levels drawn. Level l is inactive while (n - 1) g_l < activate * h_eye (paper 2.3.1, h_eye the
// eye's height above the bilinear ground under it; g_l in world units along the narrower lattice
// axis, so a level is active only when it is wide enough both ways); the finest active level is
// the full square. The coarsest level is the first whose square contains the whole terrain: from
// any eye over the terrain that is the first l with 2m g_l > S (S = (samples - 1) *
// cells_per_texel lattice cells), i.e. L = 1 + ceil(log2((S + 1) / 2m)); the note's 1 + ceil(log2(2S
// / (n - 1))) asks for (2m - 1) g_l >= S, at most one level more. It is found per frame, so an eye
// beyond the terrain gets the levels it needs; the eye is first clamped to one terrain width
// beyond the border, where the rings stop following it (the finer levels are then all off the
// terrain anyway) and lattice coordinates stay far below 2^24. The covering level is never
// deactivated: from a very high eye it alone is drawn, as a full square.
//
// Culling. Instances entirely outside the terrain are dropped; the others are tested against the
// culling frustum with their box: xz clamped to the terrain (the vertex shader clamps vertices, the
// slivers are zero-area) and heights from a coarse min/max grid of samples around it, widened by
// one g_l so that the blend's neighbours are inside it. Strip pieces follow their coarse instance.
//
// Parameters. The paper fixes n = 255 (m = 64) and says triangles are then about 5 px wide in a
// 1024 x 768 window. The main parameter is `block` (m), a Knob, not a triangle width: a level-l cell
// lies (n - 1) / 4 ... (n - 1) / 2 cells of its level from the eye, so it projects to about 2K /
// (n - 1) ... 4K / (n - 1) px (K = pixels per unit of tan, 0.5 * viewport height * |proj[1][1]|):
// 3-6 px at 1024 x 768 and 90 degrees (K = 384) with n = 255, 7-15 px at 1080p and 60 degrees. The
// width follows the viewport, which the footprints (built once per terrain and parameters) cannot,
// and spreads over a factor of 2 in every ring. `cells_per_texel` is the finest lattice cell per
// sample spacing (the paper's finest level is the terrain's sample grid: 1); `strip` (1) and
// `activate` (2.5, the paper's 2.5 h) as above. All are counts or ratios of lengths: scale-free.
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <memory>
#include <vector>

#include "render/instanced.h"
#include "render/scheme.h"
#include "shaders/clipmap_params.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"
#include "terrain/parallel_rows.h"

namespace lb {
namespace {

// Names say the long axis. Strips come in three lengths (m - 1, m - 2 and 2 coarse cells: see
// strips()) along x and along z.
enum FootprintId {
  kBlock,
  kFixupX,
  kFixupZ,
  kTrimX,
  kTrimZ,
  kCentre,
  kStripX,
  kStripZ = kStripX + 3,
  kFootprintCount = kStripZ + 3
};

// Rectangle of cx x cz cells, row-major vertices, two counter-clockwise triangles a cell.
Footprint gridFootprint(const char* name, int cx, int cz) {
  Footprint f{name, {}, {}};
  for (int j = 0; j <= cz; ++j)
    for (int i = 0; i <= cx; ++i) f.vertices.emplace_back(float(i), float(j));
  auto v = [cx](int i, int j) { return uint32_t(j * (cx + 1) + i); };
  for (int j = 0; j < cz; ++j)
    for (int i = 0; i < cx; ++i)
      f.indices.insert(f.indices.end(), {v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j), v(i + 1, j + 1), v(i, j + 1)});
  return f;
}

// Zero-area triangles (v_2k, v_2k+1, v_2k+2) along a line of `cells` cells.
Footprint stripFootprint(const char* name, int cells, bool alongX) {
  Footprint f{name, {}, {}};
  for (int i = 0; i <= cells; ++i) f.vertices.emplace_back(alongX ? float(i) : 0.0f, alongX ? 0.0f : float(i));
  for (int k = 0; 2 * k + 2 <= cells; ++k)
    f.indices.insert(f.indices.end(), {uint32_t(2 * k), uint32_t(2 * k + 1), uint32_t(2 * k + 2)});
  return f;
}

// Min/max of the samples over tiles of 2^k samples (tile i spans samples i t ... (i + 1) t, sharing
// its border samples, so it bounds the bilinear surface over it), then coarser tiles of 2 x 2: a
// box query reads at most 4 x 4 tiles. At most 128 x 128 base tiles: a few hundred kB for any
// terrain, conservative boxes for the finest blocks of large terrains.
class HeightTiles {
 public:
  explicit HeightTiles(const Heightfield& hf) : width_(hf.width), height_(hf.height) {
    while ((std::max(width_, height_) - 1 + tile_ - 1) / tile_ > 128) tile_ *= 2;
    int nx = std::max(1, (width_ - 1 + tile_ - 1) / tile_), nz = std::max(1, (height_ - 1 + tile_ - 1) / tile_);
    std::vector<glm::vec2> base(size_t(nx) * size_t(nz));
    // Rows of tiles on the terrain threads (every sample is read once: 4.3 G at 65537^2); min and
    // max are exact, so the tiles are the same whatever the bands.
    parallelRows(
        nz,
        [&](int tz0, int tz1) {
          for (int tz = tz0; tz < tz1; ++tz)
            for (int tx = 0; tx < nx; ++tx) {
              glm::vec2 b(INFINITY, -INFINITY);
              for (int z = tz * tile_; z <= std::min((tz + 1) * tile_, height_ - 1); ++z) {
                const float* row = hf.h.data() + size_t(z) * size_t(width_);
                for (int x = tx * tile_; x <= std::min((tx + 1) * tile_, width_ - 1); ++x)
                  b = {std::min(b.x, row[x]), std::max(b.y, row[x])};
              }
              base[size_t(tz) * size_t(nx) + size_t(tx)] = b;
            }
        },
        1);
    mips_.push_back({nx, nz, std::move(base)});
    while (mips_.back().nx > 1 || mips_.back().nz > 1) {
      const Mip& f = mips_.back();
      Mip c{(f.nx + 1) / 2, (f.nz + 1) / 2, {}};
      c.b.assign(size_t(c.nx) * size_t(c.nz), glm::vec2(INFINITY, -INFINITY));
      for (int z = 0; z < f.nz; ++z)
        for (int x = 0; x < f.nx; ++x) {
          glm::vec2& b = c.b[size_t(z / 2) * size_t(c.nx) + size_t(x / 2)];
          const glm::vec2& s = f.b[size_t(z) * size_t(f.nx) + size_t(x)];
          b = {std::min(b.x, s.x), std::max(b.y, s.y)};
        }
      mips_.push_back(std::move(c));
    }
  }

  // Heights of the bilinear surface over sample coordinates [u0, u1] x [w0, w1] (within the terrain).
  glm::vec2 bounds(double u0, double u1, double w0, double w1) const {
    const Mip& base = mips_[0];
    auto tiles = [&](double lo, double hi, int n) {
      int a = std::clamp(int(std::floor(lo)) / tile_, 0, n - 1);
      int b = std::clamp((std::max(int(std::ceil(hi)), 1) - 1) / tile_, a, n - 1);
      return std::array<int, 2>{a, b};
    };
    auto [x0, x1] = tiles(u0, u1, base.nx);
    auto [z0, z1] = tiles(w0, w1, base.nz);
    size_t k = 0;
    while (k + 1 < mips_.size() && ((x1 >> k) - (x0 >> k) > 3 || (z1 >> k) - (z0 >> k) > 3)) ++k;
    const Mip& lv = mips_[k];
    glm::vec2 out(INFINITY, -INFINITY);
    for (int z = z0 >> k; z <= (z1 >> k); ++z)
      for (int x = x0 >> k; x <= (x1 >> k); ++x) {
        const glm::vec2& s = lv.b[size_t(z) * size_t(lv.nx) + size_t(x)];
        out = {std::min(out.x, s.x), std::max(out.y, s.y)};
      }
    return out;
  }

 private:
  struct Mip {
    int nx, nz;
    std::vector<glm::vec2> b;
  };
  int width_, height_, tile_ = 1;
  std::vector<Mip> mips_;
};

// One frame's level: origin O (finest lattice units), spacing g, the eye in level units.
struct Level {
  int l = 0;
  long long g = 1, ox = 0, oz = 0;
  double vx = 0, vz = 0;
};

class ClipmapLod : public InstancedLod {
 public:
  ClipmapLod(const Heightfield& hf, const ParamValues& v)
      : hf_(hf),
        m_(int(v.at("block"))),
        q_(int(v.at("cells_per_texel"))),
        strip_(v.at("strip") != 0),
        activate_(v.at("activate")),
        sx_((long long)(hf.width - 1) * q_),
        sz_((long long)(hf.height - 1) * q_),
        cell_(latticeCell(hf.extent, hf.width, hf.height, double(q_))),
        tiles_(hf) {
    footprints_.resize(kFootprintCount);
    footprints_[kBlock] = gridFootprint("block", m_ - 1, m_ - 1);
    footprints_[kFixupX] = gridFootprint("fixup_x", m_ - 1, 2);
    footprints_[kFixupZ] = gridFootprint("fixup_z", 2, m_ - 1);
    footprints_[kTrimX] = gridFootprint("trim_x", 2 * m_, 1);
    footprints_[kTrimZ] = gridFootprint("trim_z", 1, 2 * m_ - 1);
    footprints_[kCentre] = gridFootprint("centre", 2, 2);
    const char* names[2][3] = {{"strip_x_long", "strip_x_short", "strip_x_fixup"},
                               {"strip_z_long", "strip_z_short", "strip_z_fixup"}};
    for (int k = 0; k < 3; ++k) {
      footprints_[size_t(kStripX + k)] = stripFootprint(names[0][k], 2 * stripCells(k), true);
      footprints_[size_t(kStripZ + k)] = stripFootprint(names[1][k], 2 * stripCells(k), false);
    }
  }

  const std::vector<Footprint>& footprints() const override { return footprints_; }

  void select(const FrameUniforms& frame, Selection& out) const override {
    out.instances.resize(kFootprintCount);
    for (auto& list : out.instances) list.clear();
    const int side = 4 * m_ - 2;
    const glm::dvec3 eye(frame.lodEye);
    const glm::dvec2 origin(frame.origin.x, frame.origin.y);
    // The eye in lattice units, at most one terrain width beyond the border (see the file comment).
    const double reach = double(std::max(sx_, sz_));
    double ex = std::clamp((eye.x - origin.x) / cell_.x, -reach, double(sx_) + reach);
    double ez = std::clamp((eye.z - origin.y) / cell_.y, -reach, double(sz_) + reach);
    if (!std::isfinite(ex) || !std::isfinite(ez)) ex = ez = 0.0;
    auto levelAt = [&](int l) {
      Level lv;
      lv.l = l;
      lv.g = 1LL << l;
      lv.vx = ex / double(lv.g);
      lv.vz = ez / double(lv.g);
      lv.ox = (2 * (long long)std::floor(lv.vx / 2) - (2 * m_ - 2)) * lv.g;
      lv.oz = (2 * (long long)std::floor(lv.vz / 2) - (2 * m_ - 2)) * lv.g;
      return lv;
    };
    auto covers = [&](const Level& lv) {
      long long span = side * lv.g;
      return lv.ox <= 0 && lv.oz <= 0 && lv.ox + span >= sx_ && lv.oz + span >= sz_;
    };
    int coarsest = 0;
    while (coarsest < 40 && !covers(levelAt(coarsest))) ++coarsest;
    // Height above the ground under the eye (clamped to the terrain outside it).
    const double ground = hf_.sample(float(eye.x - origin.x), float(eye.z - origin.y));
    const double hEye = std::max(0.0, eye.y - ground);
    const double narrow = std::min(cell_.x, cell_.y);
    int finest = 0;
    while (finest < coarsest && double(side) * double(1LL << finest) * narrow < activate_ * hEye) ++finest;

    auto recordOf = [&](const Level& lv, int w) {
      return InstanceRecord{{0.0f, 0.0f, float(lv.g), float(lv.l)},
                            {float(lv.vx), float(lv.vz), float(w), float(2 * m_ - 2 - w)}};
    };
    const int blend = (4 * m_ - 1) / 10;
    for (int l = finest; l <= coarsest; ++l) {
      const Level lv = levelAt(l);
      const bool full = l == finest;
      const InstanceRecord base = recordOf(lv, l == coarsest ? 0 : blend);
      // The finer level's square and record (rings only): its border strips go with our instances.
      const Level fine = full ? lv : levelAt(l - 1);
      const InstanceRecord fineRecord = recordOf(fine, blend);
      const long long fineSpan = side * fine.g;
      auto place = [&](int f, int px, int pz, int wx, int wz) {
        Rect r{lv.ox + px * lv.g, lv.oz + pz * lv.g, 0, 0};
        r.x1 = r.x0 + wx * lv.g;
        r.z1 = r.z0 + wz * lv.g;
        if (!emit(frame, out, f, base, lv, r) || full || !strip_) return;
        // A strip triangle is drawn exactly when the coarse instance beside it is: then no open edge of
        // the mesh overlaps another where a neighbour is culled (a coarse edge with its own strip, or
        // the strip's halves, each alone), which the analytic crack check would read as a T-junction.
        auto overlap = [](long long a0, long long a1, long long b0, long long b1) {
          return std::array<long long, 2>{std::max(a0, b0), std::min(a1, b1)};
        };
        auto [zl, zh] = overlap(r.z0, r.z1, fine.oz, fine.oz + fineSpan);
        auto [xl, xh] = overlap(r.x0, r.x1, fine.ox, fine.ox + fineSpan);
        if (zh > zl && r.x1 == fine.ox) strips(out, fineRecord, lv.g, false, fine.ox, zl, zh);
        if (zh > zl && r.x0 == fine.ox + fineSpan) strips(out, fineRecord, lv.g, false, fine.ox + fineSpan, zl, zh);
        if (xh > xl && r.z1 == fine.oz) strips(out, fineRecord, lv.g, true, fine.oz, xl, xh);
        if (xh > xl && r.z0 == fine.oz + fineSpan) strips(out, fineRecord, lv.g, true, fine.oz + fineSpan, xl, xh);
      };
      const int P[4] = {0, m_ - 1, 2 * m_, 3 * m_ - 1};
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
          if (full || !((i == 1 || i == 2) && (j == 1 || j == 2))) place(kBlock, P[i], P[j], m_ - 1, m_ - 1);
      for (int k = 0; k < 4; ++k) {
        if (!full && (k == 1 || k == 2)) continue;
        place(kFixupZ, 2 * m_ - 2, P[k], 2, m_ - 1);
        place(kFixupX, P[k], 2 * m_ - 2, m_ - 1, 2);
      }
      if (full) {
        place(kCentre, 2 * m_ - 2, 2 * m_ - 2, 2, 2);
      } else {
        // The finer level starts 0 or 1 cell of ours past the hole's low edge; the trim fills the other side.
        const bool lowX = (fine.ox - lv.ox) / lv.g - (m_ - 1) == 1, lowZ = (fine.oz - lv.oz) / lv.g - (m_ - 1) == 1;
        const int tx = lowX ? m_ - 1 : 3 * m_ - 2, tz = lowZ ? m_ - 1 : 3 * m_ - 2;
        place(kTrimX, m_ - 1, tz, 2 * m_, 1);
        place(kTrimZ, tx, lowZ ? m_ : m_ - 1, 1, 2 * m_ - 1);
      }
    }
    out.counters = {double(finest)};
  }

 private:
  struct Rect {
    long long x0, z0, x1, z1;  // finest lattice units
  };

  // Coarse cells along strip footprint k: a ring block's side, the same less the trim's cell, a fix-up's.
  int stripCells(int k) const { return k == 0 ? m_ - 1 : k == 1 ? m_ - 2 : 2; }

  // Strip pieces along the finer level's border from `lo` to `hi` on the line at `at` (lattice units,
  // along x or along z), beside one coarse instance of spacing gc. Beside a ring block or fix-up the
  // side is m - 1, m - 2 or 2 coarse cells; beside a trim bar it is the whole side, 2m - 1 cells: the
  // three lengths end to end.
  void strips(Selection& out, InstanceRecord rec, long long gc, bool alongX, long long at, long long lo,
              long long hi) const {
    const long long cells = (hi - lo) / gc;
    std::array<int, 3> pieces{0, 1, 2};
    int count = 3;
    if (cells != 2 * m_ - 1) {
      count = 0;
      for (int k = 0; k < 3 && count == 0; ++k)
        if (stripCells(k) == cells) pieces[size_t(count++)] = k;
    }
    assert(count > 0);
    // On the terrain border or beyond it a strip clamps onto the border, where no T-junction is seen.
    const long long acrossEnd = alongX ? sz_ : sx_, alongEnd = alongX ? sx_ : sz_;
    for (int i = 0; i < count; ++i) {
      const int k = pieces[size_t(i)];
      const long long end = lo + stripCells(k) * gc;
      if (at > 0 && at < acrossEnd && lo < alongEnd && end > 0) {
        rec.a.x = float(alongX ? lo : at);
        rec.a.y = float(alongX ? at : lo);
        out.instances[size_t((alongX ? kStripX : kStripZ) + k)].push_back(rec);
      }
      lo = end;
    }
  }

  // Appends footprint f over rectangle r of level `lv` unless r is off the terrain or its box outside
  // the culling frustum; says whether it did.
  bool emit(const FrameUniforms& frame, Selection& out, int f, InstanceRecord rec, const Level& lv,
            const Rect& r) const {
    const long long x0 = r.x0, z0 = r.z0, x1 = r.x1, z1 = r.z1;
    // Strictly overlapping the open terrain: a rectangle that only touches the border draws nothing.
    if (!(x0 < sx_ && x1 > 0 && z0 < sz_ && z1 > 0)) return false;
    auto clampX = [&](long long x) { return double(std::clamp(x, 0LL, sx_)); };
    auto clampZ = [&](long long z) { return double(std::clamp(z, 0LL, sz_)); };
    const glm::vec2 h =
        tiles_.bounds(clampX(x0 - lv.g) / q_, clampX(x1 + lv.g) / q_, clampZ(z0 - lv.g) / q_, clampZ(z1 + lv.g) / q_);
    const double ox = frame.origin.x, oz = frame.origin.y;
    const glm::dvec3 lo(ox + clampX(x0) * cell_.x, h.x, oz + clampZ(z0) * cell_.y);
    const glm::dvec3 hi(ox + clampX(x1) * cell_.x, h.y, oz + clampZ(z1) * cell_.y);
    for (const glm::vec4& p : frame.frustum) {
      glm::dvec3 v(p.x >= 0 ? hi.x : lo.x, p.y >= 0 ? hi.y : lo.y, p.z >= 0 ? hi.z : lo.z);
      if (double(p.x) * v.x + double(p.y) * v.y + double(p.z) * v.z + double(p.w) < 0.0) return false;
    }
    rec.a.x = float(x0);
    rec.a.y = float(z0);
    out.instances[size_t(f)].push_back(rec);
    return true;
  }

  const Heightfield& hf_;  // the renderer's terrain, which outlives its scheme state
  int m_, q_;
  bool strip_;
  double activate_;
  long long sx_, sz_;  // the terrain in lattice cells
  glm::dvec2 cell_;    // finest lattice cell, world units
  HeightTiles tiles_;
  std::vector<Footprint> footprints_;
};

class Clipmap : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = {
        .name = "clipmap",
        .description = "geometry clipmaps: nested eye-centred grids of doubling spacing, blended at ring borders",
        .seed = "Losasso & Hoppe 2004, Geometry clipmaps; Asirvatham & Hoppe, GPU Gems 2 ch. 2 (2.2-2.3.5)",
        .params = {{"block", LB_CLIPMAP_BLOCK, 64, 4, 255, true,
                    "block size m: n = 4m - 1 vertices a level side (paper: 64, n = 255)"},
                   {"cells_per_texel", LB_CLIPMAP_CELLS_PER_TEXEL, 1, 1, 16, true,
                    "finest-level cells per heightfield sample spacing"},
                   {"strip", LB_CLIPMAP_STRIP, 1, 0, 1, true,
                    "1 = degenerate triangles close each level's T-junctions; 0 = left open (negative control)"},
                   {"activate", LB_CLIPMAP_ACTIVATE, 2.5, 0, 1000, false,
                    "a level is drawn once its extent reaches this many eye heights above the ground"}},
        .mainParam = "block",
        .mainParamRole = MainParamRole::Knob,
        .front = {8, 16, 32},
        .path = DrawPath::InstancedGrid,
        .vert = "clipmap",
        .culls = true,
        // The finest level drawn: > 0 once the eye is high enough that level 0 would be under a few pixels.
        .counters = {{.frameKey = "clipmap_finest_level",
                      .caseKey = "clipmap_coarsened_frames",
                      .label = "frames without level 0"}},
    };
    return kInfo;
  }
  std::unique_ptr<InstancedLod> instancedLod(const Heightfield& hf, const ParamValues& v) const override {
    return std::make_unique<ClipmapLod>(hf, v);
  }
};

}  // namespace

const Scheme& clipmapScheme() {
  static const Clipmap scheme;
  return scheme;
}

}  // namespace lb
