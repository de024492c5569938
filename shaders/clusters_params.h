// Scheme parameter slots of `clusters` in FrameUniforms::params, shared by schemes/clusters.cpp and
// shaders/clusters.vert. The parameter shapes the CPU cut; the shader reads only the instance record.
#ifndef LB_CLUSTERS_PARAMS_H
#define LB_CLUSTERS_PARAMS_H
#define LB_CLUSTERS_MAX_ERROR_PX 0  // draw a cluster once its group's error projects under this (pixels)

// A cluster's most triangles and vertices (schemes/preprocess/cluster_dag.h): the mesh shader's
// output bounds, and local indices fit 8 bits.
#define LB_CLUSTERS_MAX_TRIANGLES 128
#define LB_CLUSTERS_MAX_VERTICES 255

// Instance record (render/instanced.h InstanceRecord), written by schemes/clusters.cpp:
//   a = (0, cluster level, cluster index, 0), b = 0 (clusters-ms reads the index).
// Footprint vertices are terrain-local lattice points (one cell a sample spacing), each a
// heightfield sample (schemes/preprocess/cluster_dag.h).
// clusters-ms's table at LB_BINDING_MESH_TABLE (schemes/clusters.cpp ClustersLod::meshTable): word 0
// the cluster count; 3 words a cluster (first vertex word, first triangle word, vertices | triangles
// << 16); a vertex word x | z << 16 (lattice point); a triangle word i0 | i1 << 8 | i2 << 16.
#endif
