// The minimal tessellation loop (`lodbench probe`): one height map, one push-constant block,
// nothing else. Heights use the same manual bilinear as common.glsl so the geometry (and the
// counters) equal lodbench's uniform scheme at the same grid, level and camera.
layout(set = 0, binding = 0) uniform sampler2D heightMap;
layout(push_constant) uniform Probe {
  mat4 viewProj;
  vec4 terrain;  // extent, level, unused, unused
} probe;

float probeHeight(vec2 worldXZ) {
  ivec2 size = textureSize(heightMap, 0);
  vec2 t = clamp(worldXZ / probe.terrain.x, 0.0, 1.0) * vec2(size - 1);
  ivec2 i0 = min(ivec2(floor(t)), max(size - 2, ivec2(0)));
  vec2 f = t - vec2(i0);
  ivec2 i1 = min(i0 + 1, size - 1);
  float h00 = texelFetch(heightMap, i0, 0).r;
  float h10 = texelFetch(heightMap, ivec2(i1.x, i0.y), 0).r;
  float h01 = texelFetch(heightMap, ivec2(i0.x, i1.y), 0).r;
  float h11 = texelFetch(heightMap, i1, 0).r;
  return mix(mix(h00, h10, f.x), mix(h01, h11, f.x), f.y);
}
