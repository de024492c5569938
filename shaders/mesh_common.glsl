// Every mesh path's mesh shader (render/mesh_drawer.cpp): its vertex outputs (terrain_vertex.glsl
// under LB_MESH_SHADER) and the histogram pass (hist_count.glsl), which a mesh shader runs itself
// for every triangle it emits when the pipeline is the histogram mode's (no geometry stage can
// follow a mesh shader). No triangle is culled here (gl_CullPrimitiveEXT is never written): the
// clipper sees every triangle, as on the path whose LOD the mesh path draws. The includer defines
// its outputs' bounds, LB_MESH_MAX_VERTICES and LB_MESH_MAX_PRIMITIVES, first.
#include "shared.h"

layout(local_size_x = LB_MESH_THREADS) in;
// Declared before the outputs, which these size.
layout(triangles, max_vertices = LB_MESH_MAX_VERTICES, max_primitives = LB_MESH_MAX_PRIMITIVES) out;

#define LB_MESH_SHADER
#include "terrain_vertex.glsl"
#include "hist_count.glsl"

layout(constant_id = 3) const bool kHistogram = false;

// A drawn triangle in the histogram pass, from its three world points (the clip positions are
// computed as emitTerrainVertex computes them).
void measureMeshTriangle(vec3 a, vec3 b, vec3 c) {
  measureTriangle(terrainClip(a), terrainClip(b), terrainClip(c), a, b, c);
}
