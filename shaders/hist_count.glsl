// The measurement pass's count of one drawn triangle (render mode Histogram): the triangle-size
// histogram's bin of its exact screen-space area (or off screen, or back-facing), its zero ground
// area (LB_HIST_DEGENERATE), and on paths with instances its world vertices for the crack check on
// the drawn mesh (metrics/mesh_cracks.h). shaders/histogram.geom calls it after the vertex or
// evaluation stage; a mesh shader, which no geometry stage can follow, for every triangle it emits.
#ifndef LB_HIST_COUNT_GLSL
#define LB_HIST_COUNT_GLSL
#include "common.glsl"

layout(set = 0, binding = LB_BINDING_HISTOGRAM, std430) buffer Histogram { uint counts[LB_HIST_COUNTERS]; } hist;
// Capacity is in triangles; past it triangles are counted, not stored.
layout(constant_id = 2) const bool kCaptureMesh = false;
layout(set = 0, binding = LB_BINDING_MESH, std430) buffer Mesh {
  uint count;
  uint capacity;
  uint pad0, pad1;
  vec4 vertices[];
}
mesh;

bool outsideOnePlane(vec4 a, vec4 b, vec4 c) {
  return (a.x > a.w && b.x > b.w && c.x > c.w) || (a.x < -a.w && b.x < -b.w && c.x < -c.w) ||
         (a.y > a.w && b.y > b.w && c.y > c.w) || (a.y < -a.w && b.y < -b.w && c.y < -c.w) ||
         (a.z > a.w && b.z > b.w && c.z > c.w) || (a.z < 0.0 && b.z < 0.0 && c.z < 0.0);
}

void countTriangle(vec4 a, vec4 b, vec4 c) {
  if (outsideOnePlane(a, b, c) || a.w <= 0.0 || b.w <= 0.0 || c.w <= 0.0) {
    atomicAdd(hist.counts[LB_HIST_OFFSCREEN], 1u);
    return;
  }
  vec2 pa = (a.xy / a.w) * 0.5 * frame.viewport.xy, pb = (b.xy / b.w) * 0.5 * frame.viewport.xy,
       pc = (c.xy / c.w) * 0.5 * frame.viewport.xy;
  // Vulkan's y points down the screen, so a terrain triangle facing the camera has a negative
  // cross product here; flip it so front-facing areas are positive.
  float signedArea = -0.5 * ((pb.x - pa.x) * (pc.y - pa.y) - (pc.x - pa.x) * (pb.y - pa.y));
  if (signedArea < 0.0) {
    atomicAdd(hist.counts[LB_HIST_BACKFACING], 1u);
    return;
  }
  // log2 binning: area in [2^(k-4), 2^(k-3)) goes to bin k.
  int bin = signedArea < 0.125 ? 0 : clamp(int(floor(log2(signedArea))) + 4, 1, LB_HIST_BINS - 1);
  atomicAdd(hist.counts[bin], 1u);
  // 64-bit fixed-point sum from two 32-bit atomics: carry into the high word on wrap-around.
  uint add = uint(min(signedArea * LB_HIST_AREA_SCALE, 4.0e9));
  uint before = atomicAdd(hist.counts[LB_HIST_AREA_LO], add);
  if (before > 0xFFFFFFFFu - add) atomicAdd(hist.counts[LB_HIST_AREA_HI], 1u);
}

// Exact in float for the cases it is meant for: equal x,z give a zero difference, and three points
// on one axis-parallel line give a zero product on each side.
bool zeroGroundArea(vec3 a, vec3 b, vec3 c) {
  vec2 u = b.xz - a.xz, v = c.xz - a.xz;
  return u.x * v.y == u.y * v.x;
}

// One drawn triangle: its clip positions and world positions, in drawing order.
void measureTriangle(vec4 ca, vec4 cb, vec4 cc, vec3 wa, vec3 wb, vec3 wc) {
  countTriangle(ca, cb, cc);
  if (zeroGroundArea(wa, wb, wc)) atomicAdd(hist.counts[LB_HIST_DEGENERATE], 1u);
  if (kCaptureMesh) {
    uint t = atomicAdd(mesh.count, 1u);
    if (t < mesh.capacity) {
      mesh.vertices[3 * t] = vec4(wa, 0.0);
      mesh.vertices[3 * t + 1] = vec4(wb, 0.0);
      mesh.vertices[3 * t + 2] = vec4(wc, 0.0);
    }
  }
}

#endif
