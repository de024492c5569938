// Scheme parameter slots of `chunked` in FrameUniforms::params, shared by schemes/chunked.cpp and
// shaders/chunked.vert. The parameters shape the offline chunk tree and the CPU selection; the
// shader reads only the instance record.
#ifndef LB_CHUNKED_PARAMS_H
#define LB_CHUNKED_PARAMS_H
#define LB_CHUNKED_MAX_ERROR_PX 0  // draw a chunk once its geometric error projects under this (pixels)
#define LB_CHUNKED_LEAF_CELLS 1    // lattice cells a side of the finest chunks
#define LB_CHUNKED_LEAF_ERROR 2    // target error of the finest chunks, in sample spacings

// Instance record (render/instanced.h InstanceRecord), written by schemes/chunked.cpp:
//   a = (skirt depth in world units, chunk level, 0, 0), b = 0.
// Footprint vertices are terrain-local lattice points (one cell a sample spacing); a skirt's
// bottom vertex is stored with x = -(x + 1) (schemes/preprocess/chunk_tree.h skirtBottomX).
#endif
