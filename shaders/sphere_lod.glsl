// NVIDIA "DirectX 11 Terrain Tessellation" (Cantlay 2011), "Hull Shader: Tessellation LOD":
// SphereToScreenSpaceTessellation, shared by the sphere, sphere-rings and density control shaders.

// Diameter in pixels of a sphere of `diameter` around the edge p0-p1, projected by the LOD camera.
// Symmetric in p0 and p1, so both patches sharing an edge get the same value.
float sphereDiameterPixels(vec3 p0, vec3 p1, float diameter) {
  vec3 centre = 0.5 * (p0 + p1);
  vec4 view0 = frame.lodView * vec4(centre, 1.0);
  vec4 view1 = view0;
  view1.x += diameter;
  vec4 clip0 = frame.lodProj * view0;
  vec4 clip1 = frame.lodProj * view1;
  clip0 /= clip0.w;
  clip1 /= clip1.w;
  clip0.xy *= frame.viewport.xy;  // NDC spans 2 units: this gives twice the pixel distance
  clip1.xy *= frame.viewport.xy;
  return 0.5 * distance(clip0.xy, clip1.xy);
}

// Projected diameter / triSize, clamped to the tessellator's range.
float sphereToScreenSpaceTessellation(vec3 p0, vec3 p1, float diameter, float triSize) {
  return clamp(sphereDiameterPixels(p0, p1, diameter) / triSize, 1.0, LB_MAX_FACTOR);
}
