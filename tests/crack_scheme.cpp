#include "crack_scheme.h"

#include "shaders/sphere_params.h"

namespace lbtest {
namespace {

class CrackScheme : public lb::Scheme {
 public:
  const lb::SchemeInfo& info() const override {
    static const lb::SchemeInfo kInfo = {
        .name = "test-crack",
        .description = "TEST ONLY: sphere LOD with mismatched shared-edge levels on purpose",
        .seed = "tests/crack_scheme.h",
        .params = {{"tri_size", LB_SPHERE_TRI_SIZE, 3, 0.5, 64, false, "target triangle width in pixels"}},
        .mainParam = "tri_size",
        .mainParamRole = lb::MainParamRole::TriangleWidthPx,
        .topology = lb::Topology::Quad4,
        .partitioning = lb::Partitioning::FractionalEven,
        .tesc = "test_crack",
        .tese = "terrain_quad",
        .culls = true,
    };
    return kInfo;
  }
};

}  // namespace

const lb::Scheme& crackScheme() {
  static const CrackScheme scheme;
  return scheme;
}

}  // namespace lbtest
