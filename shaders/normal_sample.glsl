// The normal map's filtering, one arithmetic for the raster (normals.glsl, terrain.frag) and the
// GPU ray cast (raycast.glsl), term for term as lb::sampleNormalMap (terrain/normal_map.cpp) does
// it on the CPU: level k's texel coordinate (t + 0.5) size_k / size_0 - 0.5 (t itself at level 0),
// a bilinear read with both texels of an axis clamped to the edge, the next level mixed in by the
// level's fraction, normalize as glm does. The includer defines where texels come from:
//   ivec2 nsLevelSize(int k);   level k's texels along x and z
//   void nsQuad(int k, ivec2 a, ivec2 b, out vec2 g00, out vec2 g10, out vec2 g01, out vec2 g11);
//        the gradients of texels (a.x, a.y), (b.x, a.y), (a.x, b.y), (b.x, b.y) of level k
// and may define LB_NS_DIV and LB_NS_SQRT (the ray cast's correctly rounded ones).
#ifndef LB_NORMAL_SAMPLE_GLSL
#define LB_NORMAL_SAMPLE_GLSL

#ifndef LB_NS_DIV
#define LB_NS_DIV(a, b) ((a) / (b))
#endif
#ifndef LB_NS_SQRT
#define LB_NS_SQRT(a) sqrt(a)
#endif

vec2 nsMix(vec2 a, vec2 b, float w) {
  precise vec2 r = a * (1.0 - w) + b * w;  // glm::mix
  return r;
}

vec2 nsBilinear(int k, vec2 u) {
  const ivec2 n = nsLevelSize(k);
  const vec2 fl = floor(u);
  precise vec2 f = u - fl;
  const ivec2 i0 = ivec2(fl);
  const ivec2 a = clamp(i0, ivec2(0), n - 1), b = clamp(i0 + 1, ivec2(0), n - 1);
  vec2 g00, g10, g01, g11;
  nsQuad(k, a, b, g00, g10, g01, g11);
  precise vec2 s = nsMix(nsMix(g00, g10, f.x), nsMix(g01, g11, f.x), f.y);
  return s;
}

vec2 nsLevelCoord(int k, vec2 t) {
  if (k == 0) return t;
  const vec2 s0 = vec2(nsLevelSize(0)), sk = vec2(nsLevelSize(k));
  precise vec2 scaled = (t + 0.5) * sk;
  precise vec2 u = vec2(LB_NS_DIV(scaled.x, s0.x), LB_NS_DIV(scaled.y, s0.y)) - 0.5;
  return u;
}

// t: level 0's texel coordinate (texel i's centre at i); level: shadingLevel's; levels: the map's.
vec3 nsMapNormal(vec2 t, float level, int levels) {
  const float clamped = clamp(level, 0.0, float(levels - 1));
  const int k0 = int(floor(clamped));
  precise float frac = clamped - float(k0);
  precise vec2 s = nsBilinear(k0, nsLevelCoord(k0, t));
  if (frac > 0.0) s = nsMix(s, nsBilinear(k0 + 1, nsLevelCoord(k0 + 1, t)), frac);
  precise vec3 v = vec3(s.x, 1.0, s.y);
  precise float len2 = v.x * v.x + v.y * v.y + v.z * v.z;
  precise vec3 unit = v * LB_NS_DIV(1.0, LB_NS_SQRT(len2));  // glm::normalize: v * (1 / sqrt(dot(v, v)))
  return unit;
}

#endif
