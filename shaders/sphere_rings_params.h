// Scheme parameter slots of `sphere-rings` in FrameUniforms::params, shared by schemes/sphere_rings.cpp and its
// shaders: C++ packs each parameter into its named slot, GLSL reads it by the same name, so the
// order of the C++ parameter list cannot swap them. CENTRE_X/Z are not parameters: update() writes
// the rings' per-frame centre there (lattice units, see schemes/sphere_rings_layout.h).
#ifndef LB_SPHERE_RINGS_PARAMS_H
#define LB_SPHERE_RINGS_PARAMS_H
#define LB_SPHERE_RINGS_TRI_SIZE 0
#define LB_SPHERE_RINGS_RINGS 1
#define LB_SPHERE_RINGS_POW2 2
#define LB_SPHERE_RINGS_CENTRE_X 3
#define LB_SPHERE_RINGS_CENTRE_Z 4
#endif
