// Scheme parameter slots of `cdlod` and `cdlod-sse` in FrameUniforms::params, shared by
// schemes/cdlod.cpp and shaders/cdlod.vert. Both schemes draw through cdlod.vert, so one header
// names the slots of both; only LB_CDLOD_CELLS_PER_TEXEL reaches the shader (the rest shape the CPU
// selection and the morph constants it writes into each instance record).
#ifndef LB_CDLOD_PARAMS_H
#define LB_CDLOD_PARAMS_H
#define LB_CDLOD_TRI_SIZE 0         // cdlod: target cell width in pixels at the far end of each range
#define LB_CDLOD_MORPH 1            // fraction of each range (cdlod) or of the bound (cdlod-sse) that morphs
#define LB_CDLOD_MORPH_ON 2         // 0 = morph factor forced to 0 (negative control)
#define LB_CDLOD_NODE_CELLS 3       // cells per node side at the finest level; 0 = auto
#define LB_CDLOD_CELLS_PER_TEXEL 4  // finest lattice cells per heightfield sample spacing
#define LB_CDLOD_MAX_ERROR_PX 5     // cdlod-sse: screen-space error bound per node in pixels

// Instance record (render/instanced.h InstanceRecord), written by schemes/cdlod.cpp:
//   a = (x0, z0, level + LB_CDLOD_SIDE_SHIFT * side, kNode)
//       x0, z0: the quadrant's corner in finest lattice cells; level: the node's level (cell =
//       2^level lattice cells); side: footprint cells a side (node_cells / 2).
//       kNode < 0: morph by distance with b = (morph start, morph end, 0, 0) in world units;
//       kNode >= 0: explicit morph factors, kNode inside and b = (west, south, east, north) on the
//       quadrant's edges (x = 0, z = 0, x = side, z = side).
#define LB_CDLOD_SIDE_SHIFT 32.0

// cdlod-ms (schemes/cdlod_ms.cpp): a quadrant's grid in mesh workgroups of at most this many cells
// along x and along z (powers of two, so a quadrant's side, itself one, splits into whole blocks).
// 16 x 8 is 153 vertices and 256 triangles, the most VK_EXT_mesh_shader guarantees: measured on
// the H200, a frame's mesh time grows with the mesh invocations it launches, so the largest block
// is the fastest (8 x 8: 1.8x its time, 8 x 4: 3.5x; results/published/nvidia-h200/mesh/README.md).
#ifndef LB_CDLOD_MS_BLOCK_X
#define LB_CDLOD_MS_BLOCK_X 16
#endif
#ifndef LB_CDLOD_MS_BLOCK_Z
#define LB_CDLOD_MS_BLOCK_Z 8
#endif
#endif
