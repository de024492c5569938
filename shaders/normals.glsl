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
  ivec4 header;   // x: levels; y: N, texels a page holds of its own a side; z: layers an array holds
  ivec4 level[];  // per level: texels along x and z, first page, pages along x
}
normalTable;

ivec2 nsLevelSize(int k) { return normalTable.level[k].xy; }

#define LB_NORMAL_QUAD(j)                                                            \
  g00 = texelFetch(normalPages[j], ivec3(a, layer), 0).rg;                           \
  g10 = texelFetch(normalPages[j], ivec3(b.x, a.y, layer), 0).rg;                    \
  g01 = texelFetch(normalPages[j], ivec3(a.x, b.y, layer), 0).rg;                    \
  g11 = texelFetch(normalPages[j], ivec3(b, layer), 0).rg

void nsQuad(int k, ivec2 a, ivec2 b, out vec2 g00, out vec2 g10, out vec2 g01, out vec2 g11) {
  const ivec4 lv = normalTable.level[k];
  const int n = normalTable.header.y;
  const ivec2 pages = max((lv.xy - 2) / n + 1, ivec2(1));
  const ivec2 page = min(a / n, pages - 1);
  const int index = lv.z + page.y * lv.w + page.x;
  const int array = index / normalTable.header.z, layer = index - array * normalTable.header.z;
  a -= page * n;
  b -= page * n;
  if (kNormalArrays == 1) {
    LB_NORMAL_QUAD(0);
    return;
  }
  switch (array) {
    case 1: LB_NORMAL_QUAD(1); break;
    case 2: LB_NORMAL_QUAD(2); break;
    case 3: LB_NORMAL_QUAD(3); break;
    case 4: LB_NORMAL_QUAD(4); break;
    case 5: LB_NORMAL_QUAD(5); break;
    case 6: LB_NORMAL_QUAD(6); break;
    case 7: LB_NORMAL_QUAD(7); break;
    default: LB_NORMAL_QUAD(0); break;
  }
}

#include "normal_sample.glsl"

int normalLevels() { return normalTable.header.x; }

#endif
