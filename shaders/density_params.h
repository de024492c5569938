// Scheme parameter slots of `density` in FrameUniforms::params, shared by schemes/density.cpp and its
// shaders: C++ packs each parameter into its named slot, GLSL reads it by the same name, so the
// order of the C++ parameter list cannot swap them.
#ifndef LB_DENSITY_PARAMS_H
#define LB_DENSITY_PARAMS_H
#define LB_DENSITY_THRESHOLD 0
#define LB_DENSITY_SCALE 1
#define LB_DENSITY_TRI_SIZE 2
#endif
