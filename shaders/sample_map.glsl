// A scheme's per-sample map (one float per heightfield sample: density's), stored in the heights'
// pages with their layout and table (render/sample_map_pages.h), so a terrain past one image holds
// it as it holds its heights, and the single image is again the one-page case.
#ifndef LB_SAMPLE_MAP_GLSL
#define LB_SAMPLE_MAP_GLSL
#include "heights.glsl"

layout(set = 0, binding = LB_BINDING_SAMPLE_MAP) uniform sampler2DArray samplePages[LB_HEIGHT_ARRAYS];

// The map at sample s through a cursor that holds s (sampleCursorSeek), from array k: k a constant,
// since descriptor arrays are indexed by constants alone here (no descriptor-indexing feature).
#define LB_SAMPLE_AT(k, s, c) texelFetch(samplePages[k], ivec3((s) - (c).lo, (c).layer), 0).r

// A walk over neighbouring samples (density's edges, up to a page's side of samples each) reads
// runs of them in one page: a cursor keeps the page's stored window and table entry, so the
// table is read once per page crossed, and the walker can choose the page's array once per run
// (a choice per sample, inside the loop, kept the GPU from overlapping the fetches).
struct SampleCursor {
  ivec2 lo, hi;  // the page's stored samples [lo, hi)
  int array, layer;
};

SampleCursor sampleCursor() { return SampleCursor(ivec2(0), ivec2(0), 0, 0); }

bool sampleCursorHolds(ivec2 s, SampleCursor c) { return all(greaterThanEqual(s, c.lo)) && all(lessThan(s, c.hi)); }

// Moves the cursor to the page of sample s (inside the terrain).
void sampleCursorSeek(ivec2 s, inout SampleCursor c) {
  const ivec2 page = pageOf(s);
  const uint e = heightTable.entry[page.y * heightTable.pages.x + page.x];
  c.lo = page * heightTable.samples.zw;
  c.hi = c.lo + heightTable.samples.zw + 1;  // with the shared border: the same value as the next page's
  c.array = int((e >> LB_PAGE_ARRAY_SHIFT) & LB_PAGE_ARRAY_MASK);
  c.layer = int(e & LB_PAGE_LAYER_MASK);
}

#endif
