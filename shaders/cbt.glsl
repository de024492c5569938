// The concurrent binary tree of `cbt` (schemes/cbt.cpp says the rules): the leaf bitfield and its
// sum reduction in one state buffer, leaf decoding, the longest-edge-bisection geometry of a node
// and its same-depth neighbours, and the split rule. Read by the scheme's compute passes.
#ifndef LB_CBT_GLSL
#define LB_CBT_GLSL
#include "common.glsl"
#include "cbt_params.h"

layout(set = 0, binding = LB_BINDING_LOD_STATE, std430) buffer LodState { uint words[]; }
state;

uint cbtDepth() { return state.words[LB_CBT_DEPTH]; }
uint cbtWords() { return 1u << (cbtDepth() - 5u); }                  // the bitfield's
uint cbtRead() { return LB_CBT_HEADER + cbtWords(); }                // the reduced bitfield's copy
uint cbtSums() { return LB_CBT_HEADER + 2u * cbtWords(); }           // heap index 2^l + k
uint cbtLeaves() { return state.words[cbtSums() + 1u]; }

// The bit standing for node `id` of depth d: its leftmost descendant at depth D. A leaf holds exactly
// one set bit in its subtree, there; splitting node id sets the bit of its second child 2 id + 1.
uint cbtBitOf(uint id, uint d) { return (id - (1u << d)) << (cbtDepth() - d); }

// Set bits under node id of depth d as of the last reduction: the stored sums down to one word a
// node, bitCount of the reduction's copy of the bitfield below (the update pass changes the
// bitfield itself while its threads still decode leaves). 0 or 1: a leaf or a node that does not
// exist; 2 or more: the node is split.
uint cbtCount(uint id, uint d) {
  uint D = cbtDepth();
  if (d + 5u <= D) return state.words[cbtSums() + id];
  uint bit = cbtBitOf(id, d), span = 1u << (D - d);
  uint w = state.words[cbtRead() + (bit >> 5u)] >> (bit & 31u);
  return bitCount(span == 32u ? w : w & ((1u << span) - 1u));
}

void cbtSplit(uint id, uint d) {
  uint bit = cbtBitOf(2u * id + 1u, d + 1u);
  atomicOr(state.words[LB_CBT_HEADER + (bit >> 5u)], 1u << (bit & 31u));
}
void cbtUnsplit(uint id, uint d) {
  uint bit = cbtBitOf(2u * id + 1u, d + 1u);
  atomicAnd(state.words[LB_CBT_HEADER + (bit >> 5u)], ~(1u << (bit & 31u)));
}

// Leaf `i` (0 ... leaves - 1, left to right): its node id; depth = findMSB(id).
uint cbtLeaf(uint i) {
  uint id = 1u, d = 0u, D = cbtDepth();
  while (d < D && cbtCount(id, d) > 1u) {
    uint left = cbtCount(2u * id, d + 1u);
    id = 2u * id + (i < left ? 0u : 1u);
    i -= i < left ? 0u : left;
    ++d;
  }
  return id;
}

// Triangle (a, b, c) of node id (depth >= 1) in lattice units of a 2^L square, counter-clockwise in
// (x, z): hypotenuse a-c, right angle at b. Nodes 2 and 3 halve the square along (0,0)-(2^L,2^L);
// bisecting at m = (a + c) / 2 gives child 0 = (b, m, a) and child 1 = (c, m, b). Integers: every
// corner down to depth D is a multiple of the leaf's micro cell.
void cbtTriangle(uint id, out ivec2 a, out ivec2 b, out ivec2 c) {
  int g = 1 << int(state.words[LB_CBT_LATTICE_LOG2]);
  int d = findMSB(id);
  bool second = ((id >> uint(d - 1)) & 1u) != 0u;
  a = second ? ivec2(g, g) : ivec2(0, 0);
  b = second ? ivec2(0, g) : ivec2(g, 0);
  c = second ? ivec2(0, 0) : ivec2(g, g);
  for (int k = d - 2; k >= 0; --k) {
    ivec2 m = (a + c) / 2;
    if (((id >> uint(k)) & 1u) == 0u) {
      ivec2 olda = a;
      a = b, b = m, c = olda;
    } else {
      ivec2 oldb = b;
      a = c, b = m, c = oldb;
    }
  }
}

// The same-depth node across the hypotenuse of node id (0: the square's border). Carried down from
// the roots with the neighbours across both legs: child 0's hypotenuse is its parent's first leg,
// which the neighbour there holds as its second leg (its child 1), and symmetrically for child 1;
// tests/cbt_reference.cpp checks the rule against the geometry.
uint cbtEdgeNeighbour(uint id) {
  int d = findMSB(id);
  uint self = 2u | ((id >> uint(d - 1)) & 1u);
  uvec3 n = uvec3(self ^ 1u, 0u, 0u);  // (hypotenuse, first leg, second leg)
  for (int k = d - 2; k >= 0; --k) {
    uint bit = (id >> uint(k)) & 1u;
    uvec3 c = uvec3(n.x == 0u ? 0u : 2u * n.x, n.y == 0u ? 0u : 2u * n.y, n.z == 0u ? 0u : 2u * n.z);
    n = bit == 0u ? uvec3(n.y == 0u ? 0u : c.y + 1u, 2u * self + 1u, n.x == 0u ? 0u : c.x + 1u)
                  : uvec3(c.z, c.x, 2u * self);
    self = 2u * self + bit;
  }
  return n.x;
}

// World x, z of an integer lattice point: one expression everywhere, so a corner two leaves share
// is bit-identical in both.
vec2 cbtWorld(vec2 lattice) {
  precise vec2 local = lattice * (frame.terrain.x / float(1 << int(state.words[LB_CBT_LATTICE_LOG2])));
  precise vec2 world = frame.origin.xy + local;
  return world;
}

// The split rule of LEB2D: split while the leaf's micro-hypotenuse projects to more than t / sqrt 2
// pixels (its LoD = 2 + 2 log2(px / t) > 1), taking the projection at the hypotenuse's midpoint,
// with heights; so at rest micro-hypotenuses are t/2 ... t/sqrt 2 px. Never outside the frustum.
bool cbtWantsSplit(uint id) {
  ivec2 a, b, c;
  cbtTriangle(id, a, b, c);
  vec2 wa = cbtWorld(vec2(a)), wb = cbtWorld(vec2(b)), wc = cbtWorld(vec2(c));
  if (schemeParam(LB_CBT_CULL) > 0.5) {
    vec3 lo = vec3(min(wa, min(wb, wc)), 0.0).xzy, hi = vec3(max(wa, max(wb, wc)), 0.0).xzy;
    lo.y = uintBitsToFloat(state.words[LB_CBT_MIN_HEIGHT]);
    hi.y = uintBitsToFloat(state.words[LB_CBT_MAX_HEIGHT]);
    if (boxOutsideFrustum(lo, hi)) return false;
  }
  vec3 pa = vec3(wa.x, terrainHeight(wa), wa.y), pc = vec3(wc.x, terrainHeight(wc), wc.y);
  vec2 mid = 0.5 * (wa + wc);
  vec3 pm = vec3(mid.x, terrainHeight(mid), mid.y);
  float dist = max(distance(pm, frame.lodEye.xyz), 1e-30);
  float pxPerUnit = 0.5 * frame.viewport.y * abs(frame.lodProj[1][1]);  // pixels per unit at distance 1 (y is flipped)
  float microPx = distance(pa, pc) * pxPerUnit / (dist * exp2(schemeParam(LB_CBT_SUBD)));
  return microPx * sqrt(2.0) > schemeParam(LB_CBT_TRI_SIZE);
}
#endif
