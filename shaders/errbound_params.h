// Scheme parameter slots of `errbound` in FrameUniforms::params, shared by schemes/errbound.cpp and
// shaders/errbound.tesc.
#ifndef LB_ERRBOUND_PARAMS_H
#define LB_ERRBOUND_PARAMS_H
#define LB_ERRBOUND_MAX_ERROR_PX 0
// Capture slot (of LB_CAPTURE_STRIDE floats per patch) after the 6 levels: 1 where a drawn patch
// would need more than level 64 to meet the bound, else 0.
#define LB_ERRBOUND_CAPTURE_UNMET 6
#endif
