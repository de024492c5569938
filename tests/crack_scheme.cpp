#include "crack_scheme.h"

#include "shaders/sphere_params.h"

namespace lbtest {
namespace {

class CrackScheme : public lb::Scheme {
 public:
  const lb::SchemeInfo& info() const override {
    static const lb::SchemeInfo kInfo = {
        "test-crack",
        "TEST ONLY: sphere LOD with mismatched shared-edge levels on purpose",
        "tests/crack_scheme.h",
        {{"tri_size", LB_SPHERE_TRI_SIZE, 3, 0.5, 64, false, "target triangle width in pixels"}},
        lb::Topology::Quad4,
        lb::Partitioning::FractionalEven,
        "test_crack",
        "terrain_quad",
        true,
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
