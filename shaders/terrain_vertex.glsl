// What every draw path emits per vertex: world position, level (the heat map's "equivalent
// level") and clip position. The tessellation evaluation shaders call emitTerrainVertex after their
// own level choice; the instanced path's vertex shaders (one per scheme) after their placement; a
// mesh shader (LB_MESH_SHADER) for each vertex of its workgroup's output.
#include "common.glsl"

#ifdef LB_MESH_SHADER
layout(location = 0) out vec3 outWorld[];
layout(location = 1) out float outLevel[];

// Clip position of a world point, as every path computes it (the histogram pass recomputes it).
vec4 terrainClip(vec3 world) { return frame.viewProj * vec4(world, 1.0); }

void emitTerrainVertex(uint i, vec3 world, float level) {
  outWorld[i] = world;
  outLevel[i] = level;
  gl_MeshVerticesEXT[i].gl_Position = terrainClip(world);
}
#else
layout(location = 0) out vec3 outWorld;
layout(location = 1) out float outLevel;

void emitTerrainVertex(vec3 world, float level) {
  outWorld = world;
  outLevel = level;
  gl_Position = frame.viewProj * vec4(world, 1.0);
}
#endif

// The level a tessellated base patch (extent / grid a side) would need to reach cells of `cell`
// world units: the heat map and its legend mean the same on every draw path.
float equivalentLevel(float cell) { return frame.terrain.x / (frame.terrain.y * cell); }

#if defined(LB_INSTANCED_VERTEX) || defined(LB_MESH_SHADER)
#include "instance_records.glsl"
#ifdef LB_INSTANCED_VERTEX
// Instanced-grid path (render/instanced.h): a footprint vertex in lattice units, and the
// instance's record, read by gl_InstanceIndex (never gl_PrimitiveID: lavapipe restarts it).
layout(location = 0) in vec2 inLattice;

InstanceRecord instanceRecord() { return instances.records[gl_InstanceIndex]; }
#endif

// Finest lattice cell in world units along x and z at `cellsPerTexel` cells per sample spacing.
vec2 latticeCell(float cellsPerTexel) {
  return frame.terrain.x / ((frame.terrain.zw - 1.0) * cellsPerTexel);
}

// World x, z of an integer lattice point: one expression on every vertex, so integer-equal lattice
// points give bit-equal positions whichever instance computes them.
vec2 latticeToWorld(vec2 lattice, float cellsPerTexel) {
  precise vec2 local = lattice * latticeCell(cellsPerTexel);
  precise vec2 world = frame.origin.xy + local;
  return world;
}
#endif
