// The raster's normal map past one image (docs/tiled-heightfield.md): every level in pages of (N + 1)^2 texels in
// RG16F 2D array images, numbered level after level (terrain/normal_page_layout.h), read through
// the level table and filtered by normal_sample.glsl, the ray cast's arithmetic. A bilinear read's
// four texels are one page's, so the page size changes where texels are stored, never what a pixel reads.
#ifndef LB_NORMALS_GLSL
#define LB_NORMALS_GLSL
#include "shared.h"

layout(set = 0, binding = LB_BINDING_NORMAL_PAGES) uniform sampler2DArray normalPages[LB_NORMAL_ARRAYS];
layout(constant_id = LB_SPEC_NORMAL_ARRAYS) const int kNormalArrays = LB_NORMAL_ARRAYS;
layout(std430, set = 0, binding = LB_BINDING_NORMAL_TABLE) readonly buffer NormalTable {
  ivec4 header;   // x: levels; y: N, texels a page holds of its own a side; z: layers an array holds;
                  // w: the first level that is also one image (render/normal_pages.h; x: none)
  ivec4 level[];  // per level: texels along x and z, first page, pages along x
}
normalTable;

ivec2 nsLevelSize(int k) { return normalTable.level[k].xy; }

// The 2 x 2 texels from (a.x, a.y) of a layer: one gather a component at the corner they share,
// half a texel from any other (so no sub-texel rounding can pick other texels). Gather's order:
// x (a.x, a.y + 1), y (a.x + 1, a.y + 1), z (a.x + 1, a.y), w (a.x, a.y). Two gathers where four
// fetches were: the graphics units of some GPUs (the H100's few graphics TPCs) are bound by them.
#define LB_NORMAL_GATHER(j)                          \
  gx = textureGather(normalPages[j], corner, 0); \
  gz = textureGather(normalPages[j], corner, 1)

void nsQuad(int k, ivec2 a, ivec2 b, out vec2 g00, out vec2 g10, out vec2 g01, out vec2 g11) {
  const ivec4 lv = normalTable.level[k];
  const int n = normalTable.header.y;
  const ivec2 pages = max((lv.xy - 2) / n + 1, ivec2(1));
  const ivec2 page = min(a / n, pages - 1);
  const int index = lv.z + page.y * lv.w + page.x;
  const int array = index / normalTable.header.z, layer = index - array * normalTable.header.z;
  a -= page * n;
  b -= page * n;
  const vec3 corner = vec3((vec2(a) + 1.0) / float(n + 1), float(layer));
  vec4 gx, gz;
  if (kNormalArrays == 1) {
    LB_NORMAL_GATHER(0);
  } else {
    switch (array) {
      case 1: LB_NORMAL_GATHER(1); break;
      case 2: LB_NORMAL_GATHER(2); break;
      case 3: LB_NORMAL_GATHER(3); break;
      case 4: LB_NORMAL_GATHER(4); break;
      case 5: LB_NORMAL_GATHER(5); break;
      case 6: LB_NORMAL_GATHER(6); break;
      case 7: LB_NORMAL_GATHER(7); break;
      default: LB_NORMAL_GATHER(0); break;
    }
  }
  // A texel clamped onto its neighbour (the level's edge) is that neighbour, as the fetches read it.
  g00 = vec2(gx.w, gz.w);
  g10 = b.x > a.x ? vec2(gx.z, gz.z) : g00;
  g01 = b.y > a.y ? vec2(gx.x, gz.x) : g00;
  g11 = b.x > a.x ? (b.y > a.y ? vec2(gx.y, gz.y) : g10) : g01;
}

#include "normal_sample.glsl"

int normalLevels() { return normalTable.header.x; }
int normalCoarseFrom() { return normalTable.header.w; }

#endif
