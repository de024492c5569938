// Shared by the triangle evaluation shaders: the triangle domain, the control shader's outputs
// (corner positions, unit corner normals, the shape factor) and the outputs terrain.frag reads.
// Include after terrain_vertex.glsl; SPACING is set per build variant.
layout(triangles, SPACING, ccw) in;
layout(location = 0) in vec3 inPos[];
layout(location = 1) in vec3 inNormal[];
layout(location = 2) patch in float inShape;

// Barycentric interpolation of the corners: the flat triangle (exactly a corner at a corner).
vec3 flatPoint() {
  vec3 b = gl_TessCoord;
  precise vec3 p = b.x * inPos[0] + b.y * inPos[1] + b.z * inPos[2];
  return p;
}

void emitVertex(vec3 world) {
  // Heat map shows the edge level on patch borders and the inner level inside.
  vec3 b = gl_TessCoord;
  float level = gl_TessLevelInner[0];
  if (b.x == 0.0) level = gl_TessLevelOuter[0];
  else if (b.y == 0.0) level = gl_TessLevelOuter[1];
  else if (b.z == 0.0) level = gl_TessLevelOuter[2];
  emitTerrainVertex(world, level);
}
