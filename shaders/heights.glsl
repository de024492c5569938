// The one way a shader reads the heightfield (docs/tiled-heightfield.md): pages of (P + 1)^2 samples
// with a shared +x/+z border in 2D array images, found through the page table, so a cell's four
// corners are one table lookup and four texelFetches of one layer. terrain/page_layout.h is the
// same layout in C++; the single image is its one-page case, so every scheme reads the same floats
// whether the terrain is one page or many.
#ifndef LB_HEIGHTS_GLSL
#define LB_HEIGHTS_GLSL
#include "shared.h"

layout(set = 0, binding = LB_BINDING_HEIGHT) uniform sampler2DArray heightPages[LB_HEIGHT_ARRAYS];
layout(constant_id = LB_SPEC_HEIGHT_ARRAYS) const int kHeightArrays = LB_HEIGHT_ARRAYS;
layout(std430, set = 0, binding = LB_BINDING_HEIGHT_TABLE) readonly buffer HeightTable {
  ivec4 samples;  // xy: the terrain's samples; zw: cells a page holds
  ivec4 pages;    // xy: pages along x and z
  uint entry[];
}
heightTable;

ivec2 terrainSamples() { return heightTable.samples.xy; }

// The page holding sample (or cell) s, and s in that page's own samples.
ivec2 pageOf(ivec2 s) { return min(s / heightTable.samples.zw, heightTable.pages.xy - 1); }

// Constant indices into the descriptor array in every branch: no descriptor-indexing feature is
// needed, and the array is the same for the four corners of a cell.
#define LB_PAGE_FETCH(k) texelFetch(heightPages[k], p, 0).r
#define LB_PAGE_QUAD(k)                                                                                        \
  vec4(texelFetch(heightPages[k], p, 0).r, texelFetch(heightPages[k], p + ivec3(1, 0, 0), 0).r,                \
       texelFetch(heightPages[k], p + ivec3(0, 1, 0), 0).r, texelFetch(heightPages[k], p + ivec3(1, 1, 0), 0).r)

// Where sample s lives: (x, z) in its page and the page's layer; `array` its array.
ivec3 pageTexel(ivec2 s, out int array) {
  const ivec2 page = pageOf(s);
  const uint e = heightTable.entry[page.y * heightTable.pages.x + page.x];
  array = int((e >> LB_PAGE_ARRAY_SHIFT) & LB_PAGE_ARRAY_MASK);
  return ivec3(s - page * heightTable.samples.zw, int(e & LB_PAGE_LAYER_MASK));
}

// One sample, s inside the terrain.
float heightAt(ivec2 s) {
  int array;
  const ivec3 p = pageTexel(s, array);
  if (kHeightArrays == 1) return LB_PAGE_FETCH(0);
  switch (array) {
    case 1: return LB_PAGE_FETCH(1);
    case 2: return LB_PAGE_FETCH(2);
    case 3: return LB_PAGE_FETCH(3);
    case 4: return LB_PAGE_FETCH(4);
    case 5: return LB_PAGE_FETCH(5);
    case 6: return LB_PAGE_FETCH(6);
    case 7: return LB_PAGE_FETCH(7);
    default: return LB_PAGE_FETCH(0);
  }
}

// The four corners of cell i0 (0 <= i0 <= samples - 2): h00, h10, h01, h11, from the cell's one page.
vec4 cellCorners(ivec2 i0) {
  int array;
  const ivec3 p = pageTexel(i0, array);
  if (kHeightArrays == 1) return LB_PAGE_QUAD(0);
  switch (array) {
    case 1: return LB_PAGE_QUAD(1);
    case 2: return LB_PAGE_QUAD(2);
    case 3: return LB_PAGE_QUAD(3);
    case 4: return LB_PAGE_QUAD(4);
    case 5: return LB_PAGE_QUAD(5);
    case 6: return LB_PAGE_QUAD(6);
    case 7: return LB_PAGE_QUAD(7);
    default: return LB_PAGE_QUAD(0);
  }
}

#endif
