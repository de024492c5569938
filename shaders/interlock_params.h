// Scheme parameter slots of `interlock` in FrameUniforms::params, shared by schemes/interlock.cpp and its
// shaders: C++ packs each parameter into its named slot, GLSL reads it by the same name, so the
// order of the C++ parameter list cannot swap them.
#ifndef LB_INTERLOCK_PARAMS_H
#define LB_INTERLOCK_PARAMS_H
#define LB_INTERLOCK_DMIN 0
#define LB_INTERLOCK_DMAX 1
#define LB_INTERLOCK_MIN_LOD 2
#define LB_INTERLOCK_MAX_LOD 3
#define LB_INTERLOCK_CULL 4
#endif
