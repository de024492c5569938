// A scheme's per-sample map (one float per heightfield sample: density's), stored in the heights'
// pages with their layout and table (render/sample_map_pages.h), so a terrain past one image holds
// it as it holds its heights, and the single image is again the one-page case.
#ifndef LB_SAMPLE_MAP_GLSL
#define LB_SAMPLE_MAP_GLSL
#include "heights.glsl"

layout(set = 0, binding = LB_BINDING_SAMPLE_MAP) uniform sampler2DArray samplePages[LB_HEIGHT_ARRAYS];

#define LB_SAMPLE_FETCH(k) texelFetch(samplePages[k], p, 0).r

// The map at sample s (inside the terrain). A walk over neighbouring samples (density's edges, up
// to a page's side of samples each) reads runs of them in one page: the cursor keeps the page's
// stored window and table entry, so the table is read once per page crossed, not once per sample.
struct SampleCursor {
  ivec2 lo, hi;  // the page's stored samples [lo, hi)
  int array, layer;
};

SampleCursor sampleCursor() { return SampleCursor(ivec2(0), ivec2(0), 0, 0); }

float sampleMapAt(ivec2 s, inout SampleCursor c) {
  if (any(lessThan(s, c.lo)) || any(greaterThanEqual(s, c.hi))) {
    const ivec2 page = pageOf(s);
    const uint e = heightTable.entry[page.y * heightTable.pages.x + page.x];
    c.lo = page * heightTable.samples.zw;
    c.hi = c.lo + heightTable.samples.zw + 1;  // with the shared border: the same value as the next page's
    c.array = int((e >> LB_PAGE_ARRAY_SHIFT) & LB_PAGE_ARRAY_MASK);
    c.layer = int(e & LB_PAGE_LAYER_MASK);
  }
  const ivec3 p = ivec3(s - c.lo, c.layer);
  if (kHeightArrays == 1) return LB_SAMPLE_FETCH(0);
  switch (c.array) {
    case 1: return LB_SAMPLE_FETCH(1);
    case 2: return LB_SAMPLE_FETCH(2);
    case 3: return LB_SAMPLE_FETCH(3);
    case 4: return LB_SAMPLE_FETCH(4);
    case 5: return LB_SAMPLE_FETCH(5);
    case 6: return LB_SAMPLE_FETCH(6);
    case 7: return LB_SAMPLE_FETCH(7);
    default: return LB_SAMPLE_FETCH(0);
  }
}

#endif
