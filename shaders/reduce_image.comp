#version 450
#extension GL_GOOGLE_include_directive : require
// Image a against image b (metrics/gpu_reduce.h): sums of squared and absolute RGB differences,
// counts over the threshold and changed, the histogram of each pixel's largest channel difference,
// coverage counts and crack candidates. A workgroup reads a contiguous run of pixels, folds its
// counts in shared memory and adds them to the result words once.
#include "reduce_params.h"

layout(local_size_x = LB_RED_IMAGE_GROUP) in;
layout(std430, set = 0, binding = LB_REDUCE_BINDING_A) readonly buffer ImageA { uint a[]; };
layout(std430, set = 0, binding = LB_REDUCE_BINDING_B) readonly buffer ImageB { uint b[]; };
layout(std430, set = 0, binding = LB_REDUCE_BINDING_RESULT) buffer Result { uint words[]; };

shared uint hist[256];
shared uint sums[8];

// The clear colour (magenta, alpha ignored) as image_metrics.cpp isClear reads it.
bool clearPx(uint p) { return (p & 0xffffffu) == 0xff00ffu; }
bool terrainInA(int x, int y) {
  return x >= 0 && y >= 0 && x < int(pc.width) && y < int(pc.height) && !clearPx(a[uint(y) * pc.width + uint(x)]);
}
// crackPixels' local rule: terrain of a within `reach` pixels on both sides along (dx, dy).
bool enclosed(int x, int y, int dx, int dy) {
  bool before = false, after = false;
  for (int s = 1; s <= int(pc.reach); ++s) {
    before = before || terrainInA(x - dx * s, y - dy * s);
    after = after || terrainInA(x + dx * s, y + dy * s);
  }
  return before && after;
}

// 64-bit sum as two words: the add that wraps the low word carries one into the high word.
void add64(uint at, uint v) {
  if (v == 0u) return;
  uint old = atomicAdd(words[at], v);
  if (old + v < old) atomicAdd(words[at + 1u], 1u);
}

void main() {
  uint t = gl_LocalInvocationID.x;
  hist[t] = 0u;
  if (t < 8u) sums[t] = 0u;
  barrier();
  uint n = pc.width * pc.height;
  uint first = gl_WorkGroupID.x * (LB_RED_IMAGE_GROUP * LB_RED_IMAGE_PER_THREAD);
  // Per thread at most 16 x 3 x 255^2 < 2^32; a workgroup's 4096 pixels stay below 2^32 too.
  uint sq = 0u, abssum = 0u, over = 0u, changed = 0u, missing = 0u, extra = 0u, candidates = 0u, truth = 0u;
  for (uint k = 0u; k < LB_RED_IMAGE_PER_THREAD; ++k) {
    uint i = first + k * LB_RED_IMAGE_GROUP + t;
    if (i >= n) break;
    uint pa = a[i], pb = b[i], m = 0u;
    for (uint c = 0u; c < 3u; ++c) {
      int va = int((pa >> (8u * c)) & 0xffu), vb = int((pb >> (8u * c)) & 0xffu);
      uint d = uint(abs(va - vb));
      sq += d * d;
      abssum += d;
      m = max(m, d);
    }
    over += m > pc.threshold ? 1u : 0u;
    // Bin 0 is n - changed: the host fills it, sparing the hottest shared atomic.
    if (m > 0u) {
      ++changed;
      atomicAdd(hist[m], 1u);
    }
    bool ca = clearPx(pa), cb = clearPx(pb);
    extra += !ca && cb ? 1u : 0u;
    truth += cb ? 0u : 1u;
    if (ca && !cb) {
      ++missing;
      int x = int(i % pc.width), y = int(i / pc.width);
      if (enclosed(x, y, 1, 0) || enclosed(x, y, 0, 1)) ++candidates;
    }
  }
  atomicAdd(sums[0], sq);
  atomicAdd(sums[1], abssum);
  atomicAdd(sums[2], over);
  atomicAdd(sums[3], changed);
  atomicAdd(sums[4], missing);
  atomicAdd(sums[5], extra);
  atomicAdd(sums[6], candidates);
  atomicAdd(sums[7], truth);
  barrier();
  if (hist[t] > 0u) atomicAdd(words[LB_RED_DIFF_HIST + t], hist[t]);
  if (t == 0u) {
    add64(LB_RED_SUM_SQ, sums[0]);
    add64(LB_RED_SUM_ABS, sums[1]);
    for (uint k = 2u; k < 7u; ++k)
      if (sums[k] > 0u) atomicAdd(words[LB_RED_OVER + k - 2u], sums[k]);
    if (sums[7] > 0u) atomicAdd(words[LB_RED_TRUTH_TERRAIN], sums[7]);
  }
}
