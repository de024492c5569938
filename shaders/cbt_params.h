// Scheme parameter slots of `cbt` in FrameUniforms::params and the layout of its LOD state, shared
// by schemes/cbt.cpp and the shaders: one source of truth for both sides.
#ifndef LB_CBT_PARAMS_H
#define LB_CBT_PARAMS_H
#define LB_CBT_TRI_SIZE 0         // t: target micro-triangle hypotenuse, pixels
#define LB_CBT_SUBD 1             // s: each leaf is drawn as 4^s triangles
#define LB_CBT_CELLS_PER_TEXEL 2  // q: the finest lattice cells per heightfield sample spacing
#define LB_CBT_CULL 3             // 1: leaves outside the frustum merge and never split
#define LB_CBT_POOL 4             // leaf records the renderer holds, 0 = the rule (read on the CPU only)

// State words (uint32). The header, the leaf bitfield (2^D bits), its copy as of the last reduction,
// then the sum reduction of every tree level down to one word (heap order: node k of level l at
// index 2^l + k).
#define LB_CBT_UPDATES 0       // updates run since the reset: the parity alternates split and merge
#define LB_CBT_DEPTH 1         // D, the deepest level: its leaves' micro-triangles have 1-cell legs
#define LB_CBT_LATTICE_LOG2 2  // the square is 2^L lattice units a side
#define LB_CBT_CAPACITY 3      // instance records the renderer holds (leaves past them: overflow)
#define LB_CBT_DISPATCH 4      // words 4, 5, 6: VkDispatchIndirectCommand, one thread per leaf
#define LB_CBT_LEAVES 7        // leaves after the last reduction
#define LB_CBT_OVERFLOW 8      // leaves beyond the capacity in the last update (not drawn)
#define LB_CBT_MIN_HEIGHT 9    // float bits: the terrain's lowest sample (culling boxes)
#define LB_CBT_MAX_HEIGHT 10   // float bits: its highest
#define LB_CBT_INDEX_COUNT 11  // the leaf mesh's indices (the draw's indexCount)
#define LB_CBT_HEADER 16
#define LB_CBT_GROUP 64  // threads per workgroup of the per-leaf passes
#endif
