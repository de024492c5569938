#pragma once
// A GPU-indirect scheme for the path's tests; never in the registry.
#include "render/scheme.h"

namespace lbtest {

// uniform's patches (level `level`, the footprint of render/uniform_instanced.h) chosen on the GPU:
// a first compute pass resets the draw arguments and counts the update in the LOD state, a second
// culls the base grid's patches against the frustum and writes one instance per patch it keeps
// (shaders/test_gpu_lod_*.comp), drawn with one indirect draw.
const lb::Scheme& gpuUniformScheme();

}  // namespace lbtest
