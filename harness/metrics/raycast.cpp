#include "metrics/raycast.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <thread>

#include "camera/camera_matrices.h"
#include "metrics/raycast_shade.h"
#include "shaders/footprint.h"
#include "terrain/heightfield.h"
#include "terrain/normal_map.h"
#include "terrain/parallel_rows.h"
#include "terrain/terrain_cache.h"

namespace lb {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Slack on interval ends, in ray-parameter units (the ray spans near to far plane over [0, 1]):
// a root on a shared cell border, rounded to just outside both cells, is still found.
constexpr double kEps = 1e-9;

struct Interval {
  double t0, t1;
};

// Parameter interval of o + t d inside [lo, hi] along one axis (inv = 1 / d); empty when t0 > t1.
Interval slab(double lo, double hi, double o, double d, double inv) {
  if (d == 0) return o >= lo && o <= hi ? Interval{-kInf, kInf} : Interval{kInf, -kInf};
  double a = (lo - o) * inv, b = (hi - o) * inv;
  return a < b ? Interval{a, b} : Interval{b, a};
}

// Smallest root of A s^2 + B s + C in [lo, hi], or NaN. Stable form: the root C / q does not
// cancel when A is tiny (near-planar cells, where the quadratic is almost linear).
double firstRoot(double A, double B, double C, double lo, double hi) {
  double roots[2];
  int n = 0;
  if (A == 0) {
    if (B != 0) roots[n++] = -C / B;
  } else {
    double disc = B * B - 4 * A * C;
    if (disc < 0) return std::nan("");
    double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
    if (q != 0) {
      roots[n++] = q / A;
      roots[n++] = C / q;
    } else {
      roots[n++] = 0;  // B == 0 and disc == 0, so C == 0
    }
  }
  double best = std::nan("");
  for (int i = 0; i < n; ++i)
    if (roots[i] >= lo && roots[i] <= hi && !(roots[i] >= best)) best = roots[i];
  return best;
}

}  // namespace

MaxMipmap buildMaxMipmap(const Heightfield& hf) {
  MaxMipmap m;
  MaxMipmap::Level l0;
  l0.w = std::max(hf.width - 1, 1);
  l0.h = std::max(hf.height - 1, 1);
  l0.max.resize(size_t(l0.w) * size_t(l0.h));
  // In bands of rows (terrain/parallel_rows.h): seconds of one thread at 16385^2. Each band writes
  // its own rows and takes each maximum in the order of one thread, so the pyramid is the same.
  parallelRows(l0.h, [&](int z0, int z1) {
    for (int z = z0; z < z1; ++z)
      for (int x = 0; x < l0.w; ++x)
        l0.max[size_t(z) * size_t(l0.w) + size_t(x)] =
            std::max(std::max(hf.at(x, z), hf.at(x + 1, z)), std::max(hf.at(x, z + 1), hf.at(x + 1, z + 1)));
  });
  m.levels.push_back(std::move(l0));
  while (m.levels.back().w > 1 || m.levels.back().h > 1) {
    const MaxMipmap::Level& p = m.levels.back();
    MaxMipmap::Level l;
    l.w = (p.w + 1) / 2;
    l.h = (p.h + 1) / 2;
    l.max.assign(size_t(l.w) * size_t(l.h), -std::numeric_limits<float>::infinity());
    parallelRows(l.h, [&](int r0, int r1) {  // output rows r0 .. r1 - 1: input rows 2 r0 .. 2 r1 - 1
      for (int z = 2 * r0; z < std::min(2 * r1, p.h); ++z)
        for (int x = 0; x < p.w; ++x) {
          float& v = l.max[size_t(z / 2) * size_t(l.w) + size_t(x / 2)];
          v = std::max(v, p.max[size_t(z) * size_t(p.w) + size_t(x)]);
        }
    });
    m.levels.push_back(std::move(l));
  }
  return m;
}

RayHit castRay(const Heightfield& hf, const MaxMipmap& mip, glm::dvec3 o, glm::dvec3 d, double tMin, double tMax) {
  RayHit hit;
  const int cellsX = mip.levels[0].w, cellsZ = mip.levels[0].h;
  const double cw = double(hf.extent) / double(cellsX), ch = double(hf.extent) / double(cellsZ);
  const double invX = d.x != 0 ? 1.0 / d.x : 0.0, invZ = d.z != 0 ? 1.0 / d.z : 0.0;
  struct Node {
    int level, ix, iz;
    double t0, t1;
  };
  // Interval of the ray inside node (level, ix, iz), clipped to the terrain and [tMin, tMax];
  // false when the ray misses the node or passes above its highest point.
  auto enter = [&](int level, int ix, int iz, Node& n) {
    const MaxMipmap::Level& l = mip.levels[size_t(level)];
    if (ix >= l.w || iz >= l.h) return false;
    int s = 1 << level;
    Interval x = slab(ix * s * cw, std::min((ix + 1) * s, cellsX) * cw, o.x, d.x, invX);
    Interval z = slab(iz * s * ch, std::min((iz + 1) * s, cellsZ) * ch, o.z, d.z, invZ);
    n = {level, ix, iz, std::max({tMin, x.t0, z.t0}), std::min({tMax, x.t1, z.t1})};
    if (n.t0 > n.t1 + kEps) return false;
    double yLow = std::min(o.y + n.t0 * d.y, o.y + n.t1 * d.y);
    return yLow <= double(l.max[size_t(iz) * size_t(l.w) + size_t(ix)]);
  };
  Node stack[4 * 32];
  int top = 0;
  Node root;
  if (enter(int(mip.levels.size()) - 1, 0, 0, root)) stack[top++] = root;
  while (top > 0) {
    Node n = stack[--top];
    if (n.level == 0) {
      // Bilinear cell: H(u, v) = a + b u + c v + e u v with u, v linear in the ray parameter.
      const double x0 = n.ix * cw, z0 = n.iz * ch;
      // Cells exist only where all four corners do: no clamping needed.
      const float* row = hf.h.data() + size_t(n.iz) * size_t(hf.width) + size_t(n.ix);
      const double h00 = row[0], h10 = row[1], h01 = row[hf.width], h11 = row[hf.width + 1];
      const double a = h00, b = h10 - h00, c = h01 - h00, e = h00 - h10 - h01 + h11;
      const double u0 = (o.x + n.t0 * d.x - x0) / cw, du = d.x / cw;
      const double v0 = (o.z + n.t0 * d.z - z0) / ch, dv = d.z / ch;
      const double y0 = o.y + n.t0 * d.y;
      const double C = y0 - (a + b * u0 + c * v0 + e * u0 * v0);
      const double B = d.y - (b * du + c * dv + e * (u0 * dv + v0 * du));
      const double A = -e * du * dv;
      double s = firstRoot(A, B, C, -kEps, n.t1 - n.t0 + kEps);
      if (s == s && n.t0 + s >= tMin) {
        hit.hit = true;
        hit.t = n.t0 + s;
        hit.pos = o + hit.t * d;
        // On the surface by construction; the y of the exact bilinear value keeps depth honest.
        hit.pos.y = a + b * (u0 + du * s) + c * (v0 + dv * s) + e * (u0 + du * s) * (v0 + dv * s);
        return hit;
      }
      continue;
    }
    // Children front to back: sorted by entry parameter, pushed in reverse.
    Node kids[4];
    int k = 0;
    for (int dz = 0; dz < 2; ++dz)
      for (int dx = 0; dx < 2; ++dx)
        if (enter(n.level - 1, 2 * n.ix + dx, 2 * n.iz + dz, kids[k])) ++k;
    for (int i = 1; i < k; ++i)  // insertion sort of at most 4
      for (int j = i; j > 0 && kids[j].t0 < kids[j - 1].t0; --j) std::swap(kids[j], kids[j - 1]);
    for (int i = k - 1; i >= 0; --i) stack[top++] = kids[i];
  }
  return hit;
}

void pixelRay(const glm::dmat4& inv, int px, int py, int width, int height, glm::dvec3& o, glm::dvec3& d) {
  // Pixel centre in Vulkan NDC (y down), unprojected at depth 0 (near plane) and 1 (far plane).
  double nx = (px + 0.5) / width * 2 - 1, ny = (py + 0.5) / height * 2 - 1;
  glm::dvec4 a = inv * glm::dvec4(nx, ny, 0, 1), b = inv * glm::dvec4(nx, ny, 1, 1);
  o = glm::dvec3(a) / a.w;
  d = glm::dvec3(b) / b.w - o;
}

RgbaImage raycastImage(const Heightfield& hf, const CameraPose& pose, int width, int height,
                       std::vector<float>* distance, int threads) {
  const MaxMipmap mip = buildMaxMipmap(hf);
  const std::shared_ptr<const NormalMap> shared = sharedNormalMap(hf);  // the kept terrain's, computed once
  const NormalMap& normals = *shared;
  CameraMatrices cam = cameraMatrices(pose, float(width) / float(height), hf.extent);
  const glm::dmat4 inv = glm::inverse(glm::dmat4(cam.proj) * glm::dmat4(cam.view));
  RgbaImage img{width, height, std::vector<uint8_t>(size_t(width) * size_t(height) * 4)};
  if (distance) distance->assign(size_t(width) * size_t(height), -1.0f);
  const glm::dvec3 eye(cam.eye);
  const float pixelAngle = shadingPixelAngle(cam.proj, height);
  auto rows = [&](int first, int step) {
    for (int y = first; y < height; y += step)
      for (int x = 0; x < width; ++x) {
        glm::dvec3 o, d;
        pixelRay(inv, x, y, width, height, o, d);
        RayHit h = castRay(hf, mip, o, d, 0.0, 1.0);
        size_t i = size_t(y) * size_t(width) + size_t(x);
        std::array<uint8_t, 4> c = kClearRgba;
        if (h.hit) {
          const glm::vec3 p(h.pos);  // terrain.frag's shading input: the point, and the level of its footprint
          c = shadeTerrain(normals, hf.extent, p.x, p.z,
                           shadingLevel(p, cam.eye, pixelAngle, hf.extent, hf.width, hf.height));
        }
        std::copy(c.begin(), c.end(), img.px.begin() + long(i * 4));
        if (distance && h.hit) (*distance)[i] = float(glm::length(h.pos - eye));
      }
  };
  int n = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
  n = std::min(n, height);
  // Interleaved rows balance the load: the sky rows at the top are cheap, the ground rows are not.
  std::vector<std::thread> pool;
  for (int t = 1; t < n; ++t) pool.emplace_back(rows, t, n);
  rows(0, n);
  for (auto& t : pool) t.join();
  return img;
}

}  // namespace lb
