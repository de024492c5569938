// Scheme parameter slots of `uniform` in FrameUniforms::params, shared by schemes/uniform.cpp and its
// shaders: C++ packs each parameter into its named slot, GLSL reads it by the same name, so the
// order of the C++ parameter list cannot swap them.
#ifndef LB_UNIFORM_PARAMS_H
#define LB_UNIFORM_PARAMS_H
#define LB_UNIFORM_LEVEL 0
#endif
