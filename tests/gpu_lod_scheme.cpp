#include "gpu_lod_scheme.h"

#include <cstring>

#include "render/uniform_instanced.h"
#include "shaders/uniform_params.h"
#include "terrain/heightfield.h"

namespace lbtest {
namespace {

uint32_t bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

class GpuUniform : public lb::Scheme {
 public:
  const lb::SchemeInfo& info() const override {
    static const lb::SchemeInfo kInfo = {
        .name = "test-gpu-uniform",
        .description = "TEST ONLY: uniform's patches culled and emitted by compute passes, drawn indirectly",
        .seed = "tests/gpu_lod_scheme.h",
        .params = {{"level", LB_UNIFORM_LEVEL, 8, 1, 64, true, "cells per patch side"}},
        .mainParam = "level",
        .path = lb::DrawPath::GpuIndirect,
        .vert = "uniform_instanced",
    };
    return kInfo;
  }
  lb::GpuLod gpuLod(const lb::Heightfield& hf, const lb::ParamValues& v, const lb::GpuLodBudget&) const override {
    auto grid =
        lb::uniformInstancedScheme().instancedLod(hf, {{"level", v.at("level")}, {"diagonal", 2}, {"split", 1}});
    lb::GpuLod g;
    g.footprint = grid->footprints()[0];
    g.initialState = {0, bits(hf.minHeight), bits(hf.maxHeight), uint32_t(g.footprint.indices.size())};
    g.maxInstances = 256 * 256;  // grids up to 256 patches a side
    g.passes = {{"test_gpu_lod_begin", 1}, {"test_gpu_lod_cull", 16}};
    return g;
  }
};

}  // namespace

const lb::Scheme& gpuUniformScheme() {
  static const GpuUniform scheme;
  return scheme;
}

}  // namespace lbtest
