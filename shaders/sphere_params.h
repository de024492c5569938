// Scheme parameter slots of `sphere` in FrameUniforms::params, shared by schemes/sphere.cpp and its
// shaders: C++ packs each parameter into its named slot, GLSL reads it by the same name, so the
// order of the C++ parameter list cannot swap them.
#ifndef LB_SPHERE_PARAMS_H
#define LB_SPHERE_PARAMS_H
#define LB_SPHERE_TRI_SIZE 0
#define LB_SPHERE_INTEGER 1  // read by the C++ side only (Scheme::partitioning)
#endif
