// The ray-cast ground truth on the GPU: metrics/raycast.cpp castRay and metrics/raycast_shade.cpp
// shadeTerrain, one thread per pixel. Every formula keeps the CPU oracle's operation order and is
// `precise` (no fused multiply-add), so where the device runs it in double (raycast.comp) the hits,
// distances and colours are the oracle's; raycast_f32.comp (LB_RAYCAST_F32) is the same in float
// for devices without shaderFloat64.
#include "raycast_params.h"

#ifdef LB_RAYCAST_F32
#define real float
#define real2 vec2
#define real3 vec3
#define real4 vec4
#define realMat4 mat4
const real kEps = 1e-9;  // below float's resolution at 1: the slack of castRay has no effect here
const real kBig = 3e38;
#else
#define real double
#define real2 dvec2
#define real3 dvec3
#define real4 dvec4
#define realMat4 dmat4
const real kEps = 1e-9LF;  // castRay's slack on interval ends, in ray-parameter units
const real kBig = 1e300LF;  // stands for castRay's infinity (only compared, never added)
#endif

layout(local_size_x = LB_RAYCAST_GROUP, local_size_y = LB_RAYCAST_GROUP) in;
layout(std430, binding = LB_RAYCAST_BINDING_HEIGHTS) readonly buffer Heights { float heights[]; };
layout(std430, binding = LB_RAYCAST_BINDING_MIP) readonly buffer Mip { float mip[]; };
layout(std430, binding = LB_RAYCAST_BINDING_NORMALS) readonly buffer Normals { uint normals[]; };
layout(std430, binding = LB_RAYCAST_BINDING_RGBA) writeonly buffer Rgba { uint rgba[]; };
layout(std430, binding = LB_RAYCAST_BINDING_DISTANCE) writeonly buffer Distance { float dist[]; };
layout(std140, binding = LB_RAYCAST_BINDING_PARAMS) uniform Params {
  realMat4 invViewProj;  // inverse(proj * view) in double on the host, as raycastImage computes it
  real4 eye;             // xyz: cameraMatrices().eye
  real4 cell;            // x, z: cell width and depth; y: unused
  vec4 light;            // xyz: the renderer's light direction, normalised on the host; w: extent
  vec4 slopeBlend;       // x, y: smoothstep's edges (0.15, 0.35), subtracted here as the CPU does
  // Float only: the ray as affine functions of the pixel's NDC (x, y), made in double on the host:
  // origin = [0] + x [1] + y [2], direction = [3] + x [4] + y [5]. Unprojected through a float
  // inverse matrix instead (near : far is 1 : 40000), 92% of the test frames' distances were off
  // by more than 1e-5 and some rays hit another crest (measured on lavapipe).
  vec4 rays[6];
  ivec4 size;            // image width, height; heightfield width, height
  ivec4 grid;            // cells along x, z; pyramid levels; 1: write distances
  uvec4 levels[LB_RAYCAST_MAX_LEVELS];  // per level: offset into mip[], width, height
  vec4 shading;                         // x: one pixel's angle (shadingPixelAngle); y: normal map levels
  uvec4 normalLevels[LB_RAYCAST_MAX_LEVELS];  // per normal map level: offset into normals[], width, height
  ivec4 pageGrid;  // heights[] in pages (terrain/page_layout.h): cells a page holds along x and z; pages along x
};

// The ray of this pixel and castRay's reciprocals.
real3 o, d;
real invX, invZ;

// Float division and square root correctly rounded, as the CPU's: through double where it exists
// (double rounding of a quotient or root is exact for float), the device's own in float otherwise.
#ifdef LB_RAYCAST_F32
float divF(float a, float b) { return a / b; }
float sqrtF(float a) { return sqrt(a); }
#else
float divF(float a, float b) {
  precise float q = float(double(a) / double(b));
  return q;
}
float sqrtF(float a) {
  precise float r = float(sqrt(double(a)));
  return r;
}
#endif

// The level of the pixel's footprint (shaders/footprint.h) with this shader's division and root, so
// it equals the CPU's.
#define LB_FP_DIV(a, b) divF(a, b)
#define LB_FP_SQRT(a) sqrtF(a)
#include "footprint.h"

// glm's matrix times vector: (m0 x + m1 y) + (m2 z + m3 w).
real4 transform(realMat4 m, real4 v) {
  precise real4 r = (m[0] * v.x + m[1] * v.y) + (m[2] * v.z + m[3] * v.w);
  return r;
}

// castRay's slab: parameter interval of o + t d inside [lo, hi] along one axis; empty when x > y.
real2 slab(real lo, real hi, real ro, real rd, real inv) {
  if (rd == 0) return ro >= lo && ro <= hi ? real2(-kBig, kBig) : real2(kBig, -kBig);
  precise real a = (lo - ro) * inv, b = (hi - ro) * inv;
  return a < b ? real2(a, b) : real2(b, a);
}

// castRay's enter(): the ray's interval inside node (level, ix, iz) clipped to [0, 1]; false when it
// misses the node or passes above the node's highest point.
bool enterNode(int level, int ix, int iz, out real t0, out real t1) {
  t0 = 0;
  t1 = 0;
  const uvec4 l = levels[level];
  if (ix >= int(l.y) || iz >= int(l.z)) return false;
  const int s = 1 << level;
  const real2 x = slab(real(ix * s) * cell.x, real(min((ix + 1) * s, grid.x)) * cell.x, o.x, d.x, invX);
  const real2 z = slab(real(iz * s) * cell.z, real(min((iz + 1) * s, grid.y)) * cell.z, o.z, d.z, invZ);
  t0 = max(max(real(0), x.x), z.x);
  t1 = min(min(real(1), x.y), z.y);
  if (t0 > t1 + kEps) return false;
  precise real yLow = min(o.y + t0 * d.y, o.y + t1 * d.y);
  return yLow <= real(mip[l.x + uint(iz) * l.y + uint(ix)]);
}

// castRay's firstRoot: smallest root of A s^2 + B s + C in [lo, hi].
bool firstRoot(real A, real B, real C, real lo, real hi, out real best) {
  best = 0;
  precise real r0 = 0, r1 = 0;
  int n = 0;
  if (A == 0) {
    if (B != 0) r0 = -C / B, n = 1;
  } else {
    precise real disc = B * B - 4 * A * C;
    if (disc < 0) return false;
    precise real root = sqrt(disc);
    precise real q = -0.5 * (B + (B < 0 ? -root : root));
    if (q != 0) {
      r0 = q / A;
      r1 = C / q;
      n = 2;
    } else {
      n = 1;  // B == 0 and disc == 0, so C == 0: the root 0
    }
  }
  bool found = false;
  for (int i = 0; i < n; ++i) {
    real r = i == 0 ? r0 : r1;
    if (r >= lo && r <= hi && (!found || r < best)) best = r, found = true;
  }
  return found;
}

// castRay's bilinear cell: H(u, v) = a + b u + c v + e u v, u and v linear in the ray parameter.
bool hitCell(int ix, int iz, real t0, real t1, out real3 pos) {
  pos = real3(0);
  const real x0 = real(ix) * cell.x, z0 = real(iz) * cell.z;
  // The cell's page, then the cell in it: its four corners are in that page (the shared border).
  const ivec2 page = ivec2(ix, iz) / pageGrid.xy, local = ivec2(ix, iz) - page * pageGrid.xy;
  const int stride = pageGrid.x + 1;
  const int i = (page.y * pageGrid.z + page.x) * stride * (pageGrid.y + 1) + local.y * stride + local.x;
  const real h00 = heights[i], h10 = heights[i + 1], h01 = heights[i + stride], h11 = heights[i + stride + 1];
  precise real a = h00, b = h10 - h00, c = h01 - h00, e = h00 - h10 - h01 + h11;
  precise real u0 = (o.x + t0 * d.x - x0) / cell.x, du = d.x / cell.x;
  precise real v0 = (o.z + t0 * d.z - z0) / cell.z, dv = d.z / cell.z;
  precise real y0 = o.y + t0 * d.y;
  precise real C = y0 - (a + b * u0 + c * v0 + e * u0 * v0);
  precise real B = d.y - (b * du + c * dv + e * (u0 * dv + v0 * du));
  precise real A = -e * du * dv;
  real s;
  if (!firstRoot(A, B, C, -kEps, t1 - t0 + kEps, s)) return false;
  precise real t = t0 + s;
  if (!(t >= 0)) return false;
  precise real3 p = o + t * d;
  precise real U = u0 + du * s, V = v0 + dv * s;
  p.y = a + b * U + c * V + e * U * V;  // the exact bilinear value, as castRay keeps depth honest
  pos = p;
  return true;
}

// castRay: the max-mipmap quadtree front to back. Level-0 cells are intersected as soon as their
// parent is expanded, in the order castRay pops them, so only nodes of level >= 1 are stacked.
// The four children keep fixed slots (scan order, child c at dx = c & 1, dz = c >> 1) and every
// loop over them has a constant bound, so they stay in registers rather than local memory.
bool castRay(out real3 pos) {
  pos = real3(0);
  uint stack[LB_RAYCAST_STACK];
  int top = 0;
  const int root = grid.z - 1;
  real t0, t1;
  if (!enterNode(root, 0, 0, t0, t1)) return false;  // outside the terrain's box or above it
  if (root == 0) return hitCell(0, 0, t0, t1, pos);
  stack[top++] = uint(root) << 28;
  while (top > 0) {
    const uint node = stack[--top];
    const int level = int(node >> 28) - 1, x0 = 2 * int((node >> 14) & 0x3fffu), z0 = 2 * int(node & 0x3fffu);
    bool entered[4];
    real c0[4], c1[4];
    int count = 0;
    for (int c = 0; c < 4; ++c) {
      entered[c] = enterNode(level, x0 + (c & 1), z0 + (c >> 1), c0[c], c1[c]);
      count += entered[c] ? 1 : 0;
    }
    // castRay's stable insertion sort as ranks: a child goes after every child entering earlier and
    // after an equal one scanned before it. (A swap-based sort here came out of glslang and Mesa
    // 22.3's lavapipe with both children of a swap holding the same node, measured.)
    int rank[4];
    for (int i = 0; i < 4; ++i) {
      rank[i] = 0;
      for (int j = 0; j < 4; ++j)
        if (entered[j] && (j < i ? c0[j] <= c0[i] : c0[j] < c0[i])) ++rank[i];
    }
    if (level > 0) {
      for (int c = 0; c < 4; ++c)  // back to front: the nearest child on top
        if (entered[c])
          stack[top + count - 1 - rank[c]] = (uint(level) << 28) | (uint(x0 + (c & 1)) << 14) | uint(z0 + (c >> 1));
      top += count;
      continue;
    }
    for (int r = 0; r < count; ++r) {
      int pick = 0;
      for (int c = 0; c < 4; ++c)
        if (entered[c] && rank[c] == r) pick = c;
      real a = c0[0], b = c1[0];
      for (int c = 1; c < 4; ++c)
        if (pick == c) a = c0[c], b = c1[c];
      if (hitCell(x0 + (pick & 1), z0 + (pick >> 1), a, b, pos)) return true;
    }
  }
  return false;
}

// The normal map's texels for normal_sample.glsl: level after level in normals[], two halves a uint.
ivec2 nsLevelSize(int k) { return ivec2(normalLevels[k].yz); }
void nsQuad(int k, ivec2 a, ivec2 b, out vec2 g00, out vec2 g10, out vec2 g01, out vec2 g11) {
  const uint o = normalLevels[k].x, w = normalLevels[k].y;
  g00 = unpackHalf2x16(normals[o + uint(a.y) * w + uint(a.x)]);
  g10 = unpackHalf2x16(normals[o + uint(a.y) * w + uint(b.x)]);
  g01 = unpackHalf2x16(normals[o + uint(b.y) * w + uint(a.x)]);
  g11 = unpackHalf2x16(normals[o + uint(b.y) * w + uint(b.x)]);
}
#define LB_NS_DIV(a, b) divF(a, b)
#define LB_NS_SQRT(a) sqrtF(a)
#include "normal_sample.glsl"

// sampleNormalMap at terrain-local (x, z).
vec3 mapNormal(float x, float z, float level) {
  const ivec2 n = size.zw;
  precise vec2 t = clamp(vec2(divF(x, light.w), divF(z, light.w)), 0.0, 1.0) * vec2(n - 1);
  return nsMapNormal(t, level, int(shading.y));
}

uint unorm8(float v) {
  precise float x = clamp(v, 0.0, 1.0) * 255.0;
#ifdef LB_RAYCAST_F32
  return uint(floor(x + 0.5));
#else
  return uint(floor(double(x) + 0.5LF));  // std::lround: exact in double, no carry into 1.0
#endif
}

// shadeTerrain (metrics/raycast_shade.cpp), terrain.frag's shaded colour, packed R, G, B, A.
uint shade(float x, float z, float level) {
  const vec3 n = mapNormal(x, z, level);
  precise float diffuse = max(n.x * light.x + n.y * light.y + n.z * light.z, 0.0);
  precise float lit = 0.25 + 0.75 * diffuse;
  precise float slope = 1.0 - n.y;
  // From the uniforms: glslang would fold 0.35 - 0.15 in double, not in float as the CPU does.
  precise float st = clamp(divF(slope - slopeBlend.x, slopeBlend.y - slopeBlend.x), 0.0, 1.0);
  precise float blend = st * st * (3.0 - 2.0 * st);
  precise vec3 base = vec3(0.36, 0.45, 0.25) * (1.0 - blend) + vec3(0.45, 0.40, 0.35) * blend;
  precise vec3 c = base * lit;
  return unorm8(c.r) | (unorm8(max(c.g, 0.02)) << 8) | (unorm8(c.b) << 16) | (255u << 24);
}

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= size.x || p.y >= size.y) return;
  // pixelRay: the pixel centre in Vulkan NDC (y down), unprojected at depth 0 and 1.
  precise real nx = (real(p.x) + 0.5) / real(size.x) * 2 - 1, ny = (real(p.y) + 0.5) / real(size.y) * 2 - 1;
#ifdef LB_RAYCAST_F32
  precise vec3 origin = rays[0].xyz + nx * rays[1].xyz + ny * rays[2].xyz;
  precise vec3 dir = rays[3].xyz + nx * rays[4].xyz + ny * rays[5].xyz;
#else
  precise real4 a = transform(invViewProj, real4(nx, ny, 0, 1)), b = transform(invViewProj, real4(nx, ny, 1, 1));
  precise real3 origin = a.xyz / a.w, dir = b.xyz / b.w - origin;
#endif
  o = origin;
  d = dir;
  precise real rx = d.x != 0 ? 1.0 / d.x : 0.0, rz = d.z != 0 ? 1.0 / d.z : 0.0;
  invX = rx;
  invZ = rz;
  real3 pos;
  const uint i = uint(p.y) * uint(size.x) + uint(p.x);
  if (!castRay(pos)) {
    rgba[i] = 0xffff00ffu;  // kClearRgba: magenta
    if (grid.w != 0) dist[i] = -1.0;
    return;
  }
  const vec3 hit = vec3(pos);
  rgba[i] = shade(hit.x, hit.z, shadingLevel(hit, vec3(eye.xyz), shading.x, light.w, size.z, size.w));
  if (grid.w != 0) {
    precise real3 v = pos - eye.xyz;
    precise real len = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);  // glm::length
    dist[i] = float(len);
  }
}
