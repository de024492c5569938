// Scheme parameter slots of `planefit` in FrameUniforms::params (and ComputePush::params), shared
// by schemes/planefit.cpp and its shaders. The first four are distance_lod.glsl's, so they are the
// `distance` scheme's slots by definition.
#ifndef LB_PLANEFIT_PARAMS_H
#define LB_PLANEFIT_PARAMS_H
#include "distance_params.h"
#define LB_PLANEFIT_MIN_LOD LB_DISTANCE_MIN_LOD
#define LB_PLANEFIT_MAX_LOD LB_DISTANCE_MAX_LOD
#define LB_PLANEFIT_DMIN LB_DISTANCE_DMIN
#define LB_PLANEFIT_DMAX LB_DISTANCE_DMAX
#define LB_PLANEFIT_FIT 4
#define LB_PLANEFIT_ROUGHNESS 5
#endif
