// A scheme's per-sample map (one float per heightfield sample: density's), stored in the heights'
// pages with their layout and table (render/sample_map_pages.h), so a terrain past one image holds
// it as it holds its heights, and the single image is again the one-page case.
#ifndef LB_SAMPLE_MAP_GLSL
#define LB_SAMPLE_MAP_GLSL
#include "heights.glsl"

layout(set = 0, binding = LB_BINDING_SAMPLE_MAP) uniform sampler2DArray samplePages[LB_HEIGHT_ARRAYS];

#define LB_SAMPLE_FETCH(k) texelFetch(samplePages[k], p, 0).r

// The map at sample s, s inside the terrain.
float sampleMapAt(ivec2 s) {
  int array;
  const ivec3 p = pageTexel(s, array);
  if (kHeightArrays == 1) return LB_SAMPLE_FETCH(0);
  switch (array) {
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
