#pragma once
// uniform on the instanced-grid path, for the path-equivalence tests; never in the registry.
#include "render/scheme.h"

namespace lbtest {

// grid^2 instances (the renderer's grid) of one level x level grid of cells, each instance the
// footprint of one tessellated `uniform` patch at that level: the same triangles through a vertex
// shader instead of the tessellator (shaders/test_uniform_vs.vert). Parameter `diagonal` picks the
// cells' diagonal (0: from (0,0) to (1,1), 1: from (1,0) to (0,1), 2: 0 in the patch's lower-left and
// upper-right quadrants and 1 elsewhere, lavapipe's integer quad tessellation; 3: the reverse of 2). `split` > 1 cuts
// every footprint row into that many footprints, so the same triangles go out in more, smaller draws.
const lb::Scheme& uniformVsScheme();

}  // namespace lbtest
