#pragma once
// `uniform`'s workload on the instanced-grid path: the probe's instanced comparison and the
// path-equivalence tests draw it. Not in the registry: it decides no LOD, and the tessellated
// `uniform` is the baseline the comparison reports.
#include "render/scheme.h"

namespace lb {

// grid^2 instances (the renderer's grid) of one level x level grid of cells, each instance the
// footprint of one tessellated `uniform` patch at that level: the same triangles through a vertex
// shader instead of the tessellator (shaders/uniform_instanced.vert). Parameter `diagonal` picks the
// cells' diagonal (0: from (0,0) to (1,1), 1: from (1,0) to (0,1), 2: 0 in the patch's lower-left and
// upper-right quadrants and 1 elsewhere, lavapipe's integer quad tessellation; 3: the reverse of 2). `split` > 1 cuts
// every footprint row into that many footprints, so the same triangles go out in more, smaller draws.
const Scheme& uniformInstancedScheme();

}  // namespace lb
