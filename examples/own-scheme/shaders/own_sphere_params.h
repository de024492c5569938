// Parameter slots of own-sphere in FrameUniforms::params, shared by own_sphere.cpp and its shader.
#ifndef LB_OWN_SPHERE_PARAMS_H
#define LB_OWN_SPHERE_PARAMS_H
#define LB_OWN_SPHERE_TRI_SIZE 0
#define LB_OWN_SPHERE_INTEGER 1  // read by the C++ side only (Scheme::partitioning)
#endif
