// Scheme parameter slots of `clusters` in FrameUniforms::params, shared by schemes/clusters.cpp and
// shaders/clusters.vert. The parameter shapes the CPU cut; the shader reads only the instance record.
#ifndef LB_CLUSTERS_PARAMS_H
#define LB_CLUSTERS_PARAMS_H
#define LB_CLUSTERS_MAX_ERROR_PX 0  // draw a cluster once its group's error projects under this (pixels)

// Instance record (render/instanced.h InstanceRecord), written by schemes/clusters.cpp:
//   a = (0, cluster level, 0, 0), b = 0.
// Footprint vertices are terrain-local lattice points (one cell a sample spacing), each a
// heightfield sample (schemes/preprocess/cluster_dag.h).
#endif
