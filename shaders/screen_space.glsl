// Screen-space measures shared by tessellation-control shaders; include after common.glsl.
// Both use the LOD camera (frame.lodView / lodProj), which differs from the drawn one in popping passes.

// NVIDIA "DirectX 11 Terrain Tessellation" (Cantlay 2011), SphereToScreenSpaceTessellation: the
// diameter in pixels of a sphere of `diameter` centred on the edge p0-p1. Symmetric in p0 and p1, so
// both patches sharing an edge get the same value. Divide by the target triangle width for a factor.
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

// Pixel position of a world point seen by the LOD camera (GetScreenSpacePosition of the AMD samples
// the Rapp thesis builds on); false when the point is not in front of the camera.
bool lodPixelPosition(vec3 p, out vec2 px) {
  vec4 clip = frame.lodProj * (frame.lodView * vec4(p, 1.0));
  px = clip.xy / clip.w * 0.5 * frame.viewport.xy;
  return clip.w > 0.0;
}
