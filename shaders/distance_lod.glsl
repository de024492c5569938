// practical-d3d11-ch9 Listing 9.7 (ComputeScaledDistance, ComputePatchLOD), shared by the distance
// and planefit control shaders. Parameters: distance_params.h (planefit shares the slots).
// The text says the raw LOD is clamped between minLOD and maxLOD: hence the saturate.

#include "distance_params.h"

// 0 at dmin and nearer, 1 at dmax and farther, from the LOD camera. dmin and dmax are fractions
// of the terrain extent (schemes/distance.cpp), so the distance is measured in extents too.
float scaledDistance(vec3 p) {
  float d = distance(frame.lodEye.xyz, p) / terrainExtent();
  return clamp((d - schemeParam(LB_DISTANCE_DMIN)) / (schemeParam(LB_DISTANCE_DMAX) - schemeParam(LB_DISTANCE_DMIN)), 0.0, 1.0);
}

// Inverted so that close = high detail, far = low detail (Listing 9.7's comment).
float distanceLod(vec3 p) { return mix(schemeParam(LB_DISTANCE_MIN_LOD), schemeParam(LB_DISTANCE_MAX_LOD), 1.0 - scaledDistance(p)); }
