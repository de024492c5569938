// practical-d3d11-ch9 Listing 9.7 (ComputeScaledDistance, ComputePatchLOD), shared by the distance
// and planefit control shaders. Scheme parameters 0..3: min_lod, max_lod, dmin, dmax.
// The text says the raw LOD is clamped between minLOD and maxLOD: hence the saturate.

// 0 at dmin and nearer, 1 at dmax and farther, from the LOD camera.
float scaledDistance(vec3 p) {
  float d = distance(frame.lodEye.xyz, p);
  return clamp((d - schemeParam(2)) / (schemeParam(3) - schemeParam(2)), 0.0, 1.0);
}

// Inverted so that close = high detail, far = low detail (Listing 9.7's comment).
float distanceLod(vec3 p) { return mix(schemeParam(0), schemeParam(1), 1.0 - scaledDistance(p)); }
