#include "render/path_drawer.h"

namespace lb {

std::unique_ptr<PathDrawer> makePathDrawer(const PathEnv& env) {
  switch (env.scheme.info().path) {
    case DrawPath::Tessellation:
      return makePatchDrawer(env);
    case DrawPath::InstancedGrid:
      return makeInstancedGridDrawer(env);
    case DrawPath::GpuIndirect:
      return makeGpuIndirectDrawer(env);
    case DrawPath::Mesh:
      return makeMeshDrawer(env);
  }
  return nullptr;
}

}  // namespace lb
