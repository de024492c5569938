#pragma once
// A deliberately cracking scheme for the crack-metric tests; never in the registry.
#include "render/scheme.h"

namespace lbtest {

// Sphere LOD (parameter tri_size, as `sphere`) with culling, except that on every patch (i, j) with
// i + j even the u=1 level (outer[2], the edge shared with (i+1, j)) is doubled (halved above 32):
// shaders/test_crack.tesc. Quad4, fractional_even.
const lb::Scheme& crackScheme();

}  // namespace lbtest
