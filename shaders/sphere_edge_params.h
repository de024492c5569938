// Scheme parameter slots of `sphere-edge` in FrameUniforms::params (see sphere_params.h).
#ifndef LB_SPHERE_EDGE_PARAMS_H
#define LB_SPHERE_EDGE_PARAMS_H
#define LB_SPHERE_EDGE_TRI_SIZE 0
#define LB_SPHERE_EDGE_INTEGER 1  // read by the C++ side only (Scheme::partitioning)
#endif
