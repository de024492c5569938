// clusters and clusters-ms (schemes/clusters.cpp, schemes/clusters_ms.cpp): a cluster vertex, the one
// expression both routes use: its lattice point in the world at its heightfield sample, and the heat
// map's level of a cluster `dagLevel` simplifications above the finest mesh (a level halves the
// triangles: edges about sqrt(2) longer). Clusters meeting at a locked group border hold the same
// lattice points, so their shared vertices are computed from the same integers bit for bit.
vec3 clusterVertex(vec2 lattice, float dagLevel, out float level) {
  vec2 xz = latticeToWorld(lattice, 1.0);
  precise float h = terrainHeight(xz);
  vec2 cell = latticeCell(1.0);
  level = equivalentLevel(max(cell.x, cell.y) * exp2(0.5 * dagLevel));
  return vec3(xz.x, h, xz.y);
}
