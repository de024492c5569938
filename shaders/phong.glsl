// Phong tessellation (Boubekeur & Alexa 2008) as in Rapp 2011, Figure 5-13: the flat point is
// projected onto the tangent plane of each corner, and the three projections are interpolated
// barycentrically. `precise` keeps the compiler from reassociating, so a corner maps exactly onto
// itself. schemes/preprocess/phong_surface.cpp is the same arithmetic on the CPU.

// p minus its offset from `corner` along the corner's unit normal.
vec3 phongProjection(vec3 p, vec3 corner, vec3 normal) {
  precise vec3 q = p - dot(p - corner, normal) * normal;
  return q;
}

// The Phong point (shape factor 1) of the flat point p with barycentric coordinates b.
vec3 phongPoint(vec3 p, vec3 b, vec3 p0, vec3 p1, vec3 p2, vec3 n0, vec3 n1, vec3 n2) {
  precise vec3 q = b.x * phongProjection(p, p0, n0) + b.y * phongProjection(p, p1, n1) +
                   b.z * phongProjection(p, p2, n2);
  return q;
}
