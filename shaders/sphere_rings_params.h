// Scheme parameter slots of `sphere-rings` in FrameUniforms::params, shared by schemes/sphere_rings.cpp and its
// shaders: C++ packs each parameter into its named slot, GLSL reads it by the same name, so the
// order of the C++ parameter list cannot swap them.
#ifndef LB_SPHERE_RINGS_PARAMS_H
#define LB_SPHERE_RINGS_PARAMS_H
#define LB_SPHERE_RINGS_TRI_SIZE 0
#define LB_SPHERE_RINGS_RINGS 1
#define LB_SPHERE_RINGS_TILE_SIZE 2
#define LB_SPHERE_RINGS_POW2 3
#endif
