// Accuracy baseline (docs/design.md, Schemes and What is measured): the densest crack-free tessellation the device
// allows over the whole grid, integer level 64 (Vulkan's guaranteed maxTessellationGenerationLevel)
// on every edge and inside, no culling. Ground truth for the image metrics. Shader: reference.tesc.
#include "render/scheme.h"

namespace lb {
namespace {

class Reference : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = {
        .name = "reference",
        .description = "integer level 64 on every edge and inside, no culling (ground truth for image metrics)",
        .seed = "accuracy baseline: docs/design.md, Schemes and What is measured",
        .params = {},
        .mainParam = "",
        .topology = Topology::Quad4,
        .partitioning = Partitioning::Integer,
        .tesc = "reference",
    };
    return kInfo;
  }
};

}  // namespace

const Scheme& referenceScheme() {
  static const Reference scheme;
  return scheme;
}

}  // namespace lb
