// Scheme parameter slots of `phong` in FrameUniforms::params, shared by schemes/phong.cpp and its
// shaders: C++ packs each parameter into its named slot, GLSL reads it by the same name, so the
// order of the C++ parameter list cannot swap them.
#ifndef LB_PHONG_PARAMS_H
#define LB_PHONG_PARAMS_H
#define LB_PHONG_TRI_SIZE 0
#define LB_PHONG_ALPHA 1
#define LB_PHONG_FRUSTUM_TOLERANCE 2
#define LB_PHONG_BACKFACE_TOLERANCE 3
#define LB_PHONG_THRESHOLD 4
#define LB_PHONG_SCALE 5
#endif
