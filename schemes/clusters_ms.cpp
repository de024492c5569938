// clusters-ms: clusters (schemes/clusters.cpp: the Nanite-style cluster DAG and its cut) drawn by
// task and mesh shaders instead of one indexed draw per selected cluster, so clusters against
// clusters-ms is the instanced route against mesh shading at one cut. The cut is clusters' own
// object (its DAG, its parameter), its records the instance records the instanced route draws, each
// naming its cluster; the task shader (shaders/clusters_ms.task) reads one selected cluster an
// invocation and the mesh shader (shaders/clusters_ms.mesh) emits that cluster's triangles from the
// clusters' table (ClustersLod::meshTable, at most 255 vertices and 128 triangles a cluster), each
// vertex placed by the instanced route's function (shaders/clusters_vertex.glsl): the same
// triangles, the same points. clusters_unmet_clusters stays clusters' (a counter names one scheme).
// docs/draw-paths.md, "The mesh path".
#include "render/scheme.h"

namespace lb {

const Scheme& clustersScheme();

namespace {

class ClustersMs : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = [] {
      const SchemeInfo& twin = clustersScheme().info();
      return SchemeInfo{
          .name = "clusters-ms",
          .description = "clusters' cluster DAG and CPU cut, each selected cluster emitted by mesh shaders",
          .seed =
              "Karis 2021, Nanite: A Deep Dive (the DAG cut), clusters emitted by task and mesh shaders "
              "(VK_EXT_mesh_shader)",
          .params = twin.params,
          .mainParam = twin.mainParam,
          .mainParamRole = twin.mainParamRole,
          .front = twin.front,
          .path = DrawPath::Mesh,
          .task = "clusters_ms",
          .mesh = "clusters_ms",
          .meshLod = DrawPath::InstancedGrid,
      };
    }();
    return kInfo;
  }
  void validate(const ParamValues& v) const override { clustersScheme().validate(v); }
  double targetAreaPx(const ParamValues& v) const override { return clustersScheme().targetAreaPx(v); }
  std::unique_ptr<InstancedLod> instancedLod(const Heightfield& hf, const ParamValues& v) const override {
    return clustersScheme().instancedLod(hf, v);
  }
};

}  // namespace

const Scheme& clustersMsScheme() {
  static const ClustersMs scheme;
  return scheme;
}

}  // namespace lb
