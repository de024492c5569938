#version 450
#extension GL_GOOGLE_include_directive : require
// cbt, pass 1 of 4, one thread per leaf (up to the capacity: cbt_batch.comp): on even updates split
// the leaves the rule asks to split, conformingly; on odd updates merge the diamonds whose two
// parents the rule would not split. Only atomicOr on even and atomicAnd on odd updates touch the
// bitfield, and every decision reads the previous update's reduction, so the result does not depend
// on the order threads run in.
#include "cbt.glsl"

layout(local_size_x = LB_CBT_GROUP) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= state.words[LB_CBT_LEAVES]) return;
  uint id = cbtLeaf(i);
  uint d = uint(findMSB(id));
  if ((state.words[LB_CBT_UPDATES] & 1u) == 0u) {
    if (d >= cbtDepth() || !cbtWantsSplit(id)) return;
    cbtSplit(id, d);
    // A conforming split also splits the node across the hypotenuse, which needs its own parent
    // split first when that is still a leaf a level up, and so on towards the root.
    uint n = id;
    for (;;) {
      uint e = cbtEdgeNeighbour(n);
      if (e == 0u || cbtCount(e, d) >= 2u) break;
      cbtSplit(e, d);
      if (d == 1u || cbtCount(e >> 1u, d - 1u) >= 2u) break;
      n = e >> 1u;
      --d;
      cbtSplit(n, d);
    }
  } else {
    // The second child of a parent p (not a root triangle) speaks for p; p's partner across the
    // hypotenuse is decided by its own second child from the same reads.
    if ((id & 1u) == 0u || d < 2u) return;
    uint p = id >> 1u, q = cbtEdgeNeighbour(p);
    if (cbtCount(p, d - 1u) != 2u || (q != 0u && cbtCount(q, d - 1u) != 2u)) return;
    if (cbtWantsSplit(p) || (q != 0u && cbtWantsSplit(q))) return;
    cbtUnsplit(p, d - 1u);
  }
}
