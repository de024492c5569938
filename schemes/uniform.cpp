// Baseline: one fixed integer tessellation level for every patch edge and interior.
#include "render/scheme.h"
#include "shaders/uniform_params.h"

namespace lb {
namespace {

class Uniform : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = {
        .name = "uniform",
        .description = "one fixed tessellation level everywhere",
        .seed = "baseline",
        .params = {{"level", LB_UNIFORM_LEVEL, 8, 1, 64, true, "tessellation level of every edge and interior"}},
        .mainParam = "level",
        .mainParamRole = MainParamRole::UniformLevel,
        .front = {2, 4, 8},
        .topology = Topology::Quad4,
        .partitioning = Partitioning::Integer,
        .tesc = "uniform",
    };
    return kInfo;
  }
  float maxLevel(const ParamValues& v) const override { return float(v.at("level")); }
};

}  // namespace

const Scheme& uniformScheme() {
  static const Uniform scheme;
  return scheme;
}

}  // namespace lb
