// Plugins lodbench must refuse (tests/test_plugins.cpp), one per build of this file:
// BAD_PLUGIN_COLLIDES: a scheme named like a built-in one (sphere);
// BAD_PLUGIN_WRONG_API: a registration function claiming another plugin API version.
#include "schemes/plugin_api.h"

namespace {

#if BAD_PLUGIN_COLLIDES
class Impostor : public lb::Scheme {
 public:
  const lb::SchemeInfo& info() const override {
    static const lb::SchemeInfo kInfo = {.name = "sphere", .description = "a second sphere", .tesc = "sphere"};
    return kInfo;
  }
};

void addSchemes(lb::PluginSchemes& out) {
  out.push_back(std::make_unique<Impostor>());
}
#endif

}  // namespace

#if BAD_PLUGIN_COLLIDES
LODBENCH_PLUGIN("collides", addSchemes)
#endif

#if BAD_PLUGIN_WRONG_API
// Only the fields every version keeps: lodbench reads no further before it refuses.
extern "C" __attribute__((visibility("default"))) const LodbenchPlugin* lodbench_plugin() {
  static const LodbenchPlugin plugin{LODBENCH_PLUGIN_API_VERSION + 1, 0, "9.9.9", "wrong-api", nullptr, 0, nullptr};
  return &plugin;
}
#endif
