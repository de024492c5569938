#pragma once
// The plugin boundary (docs/plugins.md): a scheme library built outside this tree, against the
// installed package, exports one function, lodbench_plugin(), declared with LODBENCH_PLUGIN below.
// What a plugin may use is this header and what it includes (render/scheme.h: the scheme interface,
// parameter specs, the instanced and GPU-indirect hooks) plus render/instanced.h,
// terrain/heightfield.h, shaders/shared.h and error.h; its shaders are compiled by the package's
// lodbench_add_scheme() with lodbench's shared shader includes and linked into the library.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/scheme.h"

// Bumped with every change to what crosses the boundary: a field of SchemeInfo, ParamSpec,
// SchemeCounter, the instanced (Selection, Footprint, InstanceRecord) or GPU-indirect (GpuLod,
// GpuLodPass, GpuLodBudget) types, a virtual of Scheme or InstancedLod, FrameUniforms or
// Heightfield. A plugin built against another version is refused at load, naming both.
#define LODBENCH_PLUGIN_API_VERSION 3

namespace lb {

// SPIR-V of one of the plugin's shaders under the name the renderer loads it by
// ("own_sphere.tesc.spv", "own_sphere_integer.tese.spv"): lodbench_add_scheme() generates the table.
struct PluginShader {
  const char* name;
  const unsigned char* bytes;
  size_t size;
};

using PluginSchemes = std::vector<std::unique_ptr<Scheme>>;

// A fingerprint of the boundary's layout as this compiler sees it: catches headers changed without
// a version bump, and a plugin compiled with another C++ library ABI (another std::string size).
constexpr uint32_t pluginLayout() {
  return uint32_t(sizeof(SchemeInfo)) * 1000003u + uint32_t(sizeof(ParamSpec)) * 10007u +
         uint32_t(sizeof(GpuLod)) * 101u + uint32_t(sizeof(Selection)) * 7u + uint32_t(sizeof(std::string));
}

}  // namespace lb

extern "C" {

// What lodbench_plugin() returns. The first three fields keep their place in every version, so any
// lodbench can read them from any plugin and refuse a mismatch before it touches anything else.
struct LodbenchPlugin {
  uint32_t apiVersion;          // LODBENCH_PLUGIN_API_VERSION the plugin was compiled with
  uint32_t layout;              // lb::pluginLayout() as the plugin was compiled
  const char* lodbenchVersion;  // the lodbench whose package it was built against (messages only)
  const char* name;             // for messages and run.json
  const lb::PluginShader* shaders;
  size_t shaderCount;
  // Appends the plugin's schemes; called once, after the checks above. May throw lb::InputError.
  void (*addSchemes)(lb::PluginSchemes& out);
};

// Defined by the source lodbench_add_scheme() generates from the plugin's shaders.
extern const lb::PluginShader lodbenchPluginShaders[];
extern const size_t lodbenchPluginShaderCount;

}  // extern "C"

#ifndef LODBENCH_PLUGIN_BUILT_AGAINST
#define LODBENCH_PLUGIN_BUILT_AGAINST "unknown"
#endif

// In one source file of the plugin: LODBENCH_PLUGIN("my-schemes", addMySchemes), where
// `void addMySchemes(lb::PluginSchemes& out)` appends the plugin's schemes.
#define LODBENCH_PLUGIN(pluginName, addSchemesFunction)                                       \
  extern "C" __attribute__((visibility("default"))) const LodbenchPlugin* lodbench_plugin() { \
    static const LodbenchPlugin plugin{LODBENCH_PLUGIN_API_VERSION,                           \
                                       lb::pluginLayout(),                                    \
                                       LODBENCH_PLUGIN_BUILT_AGAINST,                         \
                                       pluginName,                                            \
                                       lodbenchPluginShaders,                                 \
                                       lodbenchPluginShaderCount,                             \
                                       addSchemesFunction};                                   \
    return &plugin;                                                                           \
  }
