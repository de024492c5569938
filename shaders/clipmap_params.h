// Scheme parameter slots of `clipmap` in FrameUniforms::params, shared by schemes/clipmap.cpp and its
// vertex shader: C++ packs each parameter into its named slot, GLSL reads it by the same name, so the
// order of the C++ parameter list cannot swap them.
#ifndef LB_CLIPMAP_PARAMS_H
#define LB_CLIPMAP_PARAMS_H
#define LB_CLIPMAP_BLOCK 0            // read by the C++ side only (footprint sizes; the record carries w)
#define LB_CLIPMAP_CELLS_PER_TEXEL 1  // lattice cells per heightfield sample spacing
#define LB_CLIPMAP_STRIP 2            // read by the C++ side only (strip instances)
#define LB_CLIPMAP_ACTIVATE 3         // read by the C++ side only (finest active level)
#endif
