// Density map lookups (AMD "Detail Tessellation 11", Density-based; Rapp 2011, 5.2.3). The map is
// schemes/preprocess/density_map.cpp's output, one value per heightfield sample, read through the
// heights' pages (sample_map.glsl). Everything here is integer arithmetic identical to
// density_map.cpp, so tests can recompute it.
#include "sample_map.glsl"

// round(i * (size - 1) / n): the texel under grid vertex index i (density_map.cpp gridTexel).
int gridTexel(int i, int n, int size) { return (2 * i * (size - 1) + n) / (2 * n); }

// Texel under grid vertex (i, j) of the N x N patch grid.
ivec2 gridVertexTexel(ivec2 v) {
  ivec2 size = terrainSamples();
  int n = int(frame.terrain.y);
  return ivec2(gridTexel(v.x, n, size.x), gridTexel(v.y, n, size.y));
}

// Round half away from zero of num / den, den > 0.
int roundDiv(int num, int den) {
  int q = (2 * abs(num) + den) / (2 * den);
  return num < 0 ? -q : q;
}

// Texel k of the walk from a over d in `steps` even steps.
ivec2 edgeTexel(ivec2 a, ivec2 d, int steps, int k) {
  return steps == 0 ? a : a + ivec2(roundDiv(k * d.x, steps), roundDiv(k * d.y, steps));
}

// The walk's texels from k on while the cursor's page holds them, from array `idx` (a constant).
#define LB_DENSITY_RUN(idx)                                 \
  for (; k <= steps; ++k) {                                 \
    const ivec2 t = edgeTexel(a, d, steps, k);              \
    if (!sampleCursorHolds(t, cursor)) break;               \
    best = max(best, LB_SAMPLE_AT(idx, t, cursor));         \
  }

// Maximum density over the texels the edge a-b crosses (seed: "for each edge ... the maximum density
// along the edge"): max(|dx|, |dz|) + 1 evenly stepped texels, walked from the lexicographically
// smaller end so both patches sharing the edge read the same texels and agree on its factor. The
// walk goes a page at a time, each page's array chosen once (sample_map.glsl).
float maxDensityAlongEdge(ivec2 a, ivec2 b) {
  if (b.x < a.x || (b.x == a.x && b.y < a.y)) {
    ivec2 t = a;
    a = b;
    b = t;
  }
  ivec2 d = b - a;
  int steps = max(abs(d.x), abs(d.y));
  float best = 0.0;
  SampleCursor cursor = sampleCursor();
  int k = 0;
  while (k <= steps) {
    sampleCursorSeek(edgeTexel(a, d, steps, k), cursor);  // holds texel k: the run below takes it
    if (kHeightArrays == 1) {
      LB_DENSITY_RUN(0)
    } else {
      switch (cursor.array) {
        case 1: LB_DENSITY_RUN(1) break;
        case 2: LB_DENSITY_RUN(2) break;
        case 3: LB_DENSITY_RUN(3) break;
        case 4: LB_DENSITY_RUN(4) break;
        case 5: LB_DENSITY_RUN(5) break;
        case 6: LB_DENSITY_RUN(6) break;
        case 7: LB_DENSITY_RUN(7) break;
        default: LB_DENSITY_RUN(0) break;
      }
    }
  }
  return best;
}
