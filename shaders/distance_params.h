// Scheme parameter slots of `distance` in FrameUniforms::params, shared by schemes/distance.cpp and its
// shaders: C++ packs each parameter into its named slot, GLSL reads it by the same name, so the
// order of the C++ parameter list cannot swap them.
#ifndef LB_DISTANCE_PARAMS_H
#define LB_DISTANCE_PARAMS_H
#define LB_DISTANCE_MIN_LOD 0
#define LB_DISTANCE_MAX_LOD 1
#define LB_DISTANCE_DMIN 2
#define LB_DISTANCE_DMAX 3
#endif
