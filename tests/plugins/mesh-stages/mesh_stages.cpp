// The smallest scheme on the mesh path (tests/plugins/mesh-stages/CMakeLists.txt says why it
// exists): sphere-ms's declaration with a task shader that launches no mesh workgroup, so it draws
// nothing wherever the device has mesh shaders and is skipped where it has none.
#include "schemes/plugin_api.h"

namespace {

class MeshStages : public lb::Scheme {
 public:
  const lb::SchemeInfo& info() const override {
    static const lb::SchemeInfo kInfo = {
        .name = "mesh-stages",
        .description = "a plugin's task and mesh shaders (they draw nothing)",
        .seed = "none: a test of the plugin build and loader",
        .path = lb::DrawPath::Mesh,
        .task = "mesh_stages",
        .mesh = "mesh_stages",
        .meshLod = lb::DrawPath::Tessellation,
        .topology = lb::Topology::Quad4,
        .partitioning = lb::Partitioning::Integer,
    };
    return kInfo;
  }
};

void addSchemes(lb::PluginSchemes& out) {
  out.push_back(std::make_unique<MeshStages>());
}

}  // namespace

LODBENCH_PLUGIN("mesh-stages", addSchemes)
