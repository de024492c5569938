#pragma once
// Out-of-tree schemes (docs/plugins.md): a shared library loaded at run time whose schemes join the
// registry (schemes/registry.h) after the built-in ones, so configs, runs, reports and compare take
// them like any other. Named in a config ("plugins") or on the command line (--plugin).
#include <cstdint>
#include <string>
#include <vector>

namespace lb {

struct LoadedPlugin {
  std::string file;    // as given
  std::string path;    // canonical
  std::string sha256;  // of the library file: its code and its shaders (compiled into it)
  uint32_t apiVersion = 0;
  std::string name;          // the plugin's own name
  std::string builtAgainst;  // the lodbench version of the package it was built against
  std::vector<std::string> schemes;
};

// Loads the library and registers its schemes and shaders. The same file with the same contents
// again is a no-op. Throws InputError naming the file and what is wrong (missing, no registration
// function, another plugin API version, a scheme or shader name already taken, a scheme needing a
// shader nobody has) before registering anything: a refused plugin leaves the registry as it was.
const LoadedPlugin& loadPlugin(const std::string& file);
// Every plugin loaded so far, in load order.
const std::vector<LoadedPlugin>& loadedPlugins();
// The plugin a scheme came from; nullptr for a built-in scheme.
const LoadedPlugin* pluginOfScheme(const std::string& scheme);
// False where this build cannot load plugins (a static C++ runtime, fuzzing), with the reason.
bool pluginsSupported(std::string* why = nullptr);

}  // namespace lb
