#include "schemes/plugins.h"

#include <dlfcn.h>

#include <filesystem>
#include <memory>

#include "error.h"
#include "render/scheme.h"
#include "schemes/plugin_api.h"
#include "schemes/registry.h"
#include "sha256.h"
#include "shaders/shared.h"
#include "version.h"
#include "vk/resources.h"

namespace lb {

namespace {

struct Registry {
  std::vector<LoadedPlugin> plugins;
  // The schemes plugins made. Never destroyed: their code lives in libraries that stay loaded to
  // the end, and a destructor run after the loader's teardown could find its library gone.
  std::vector<std::unique_ptr<Scheme>> schemes;
};

Registry& registry() {
  static Registry* r = new Registry;
  return *r;
}

std::string versionText(uint32_t api, const char* lodbench) {
  return "plugin API " + std::to_string(api) + " (lodbench " + (lodbench && *lodbench ? lodbench : "unknown") + ")";
}

// The SPIR-V file names the renderer will ask for on the scheme's behalf (render/*_drawer.cpp).
std::vector<std::string> shadersOf(const Scheme& scheme) {
  const SchemeInfo& info = scheme.info();
  std::vector<std::string> out;
  if (!info.vert.empty()) out.push_back(info.vert + ".vert.spv");
  if (!info.tesc.empty()) {
    out.push_back(info.tesc + ".tesc.spv");
    for (Partitioning p : {Partitioning::Integer, Partitioning::FractionalEven, Partitioning::FractionalOdd})
      out.push_back(info.tese + "_" + partitioningName(p) + ".tese.spv");
  }
  if (!info.task.empty()) out.push_back(info.task + ".task.spv");
  if (!info.mesh.empty()) out.push_back(info.mesh + ".mesh.spv");
  if (!info.compute.empty()) out.push_back(info.compute + ".comp.spv");
  return out;
}

// Everything the registry would refuse later, checked before anything is registered.
void checkSchemes(const std::string& where, const PluginSchemes& schemes, const LodbenchPlugin& p) {
  std::vector<std::string> seen, own;
  for (size_t i = 0; i < p.shaderCount; ++i) own.push_back(p.shaders[i].name);
  for (const auto& s : schemes) {
    if (!s) throw InputError(where + ": added an empty scheme");
    const SchemeInfo& info = s->info();
    const std::string name = info.name;
    if (name.empty() || name.find_first_of(" /\\\"'") != std::string::npos)
      throw InputError(where + ": scheme name '" + printable(name) + "' is empty or holds a space, slash or quote");
    for (const std::string& g : schemeGroupNames())
      if (name == g) throw InputError(where + ": scheme '" + name + "' has the name of a scheme group; rename it");
    if (const Scheme* taken = findScheme(name)) {
      (void)taken;
      const LoadedPlugin* other = pluginOfScheme(name);
      throw InputError(where + ": scheme '" + name + "' has the name of " +
                       (other ? "a scheme of plugin '" + other->file + "'" : "a built-in scheme (lodbench list)") +
                       "; rename it");
    }
    for (const std::string& n : seen)
      if (n == name) throw InputError(where + ": adds scheme '" + name + "' twice");
    seen.push_back(name);
    for (const ParamSpec& param : info.params)
      if (param.slot < 0 || param.slot >= 4 * LB_SCHEME_PARAM_VEC4S)
        throw InputError(where + ": scheme '" + name + "': parameter '" + param.name + "' has slot " +
                         std::to_string(param.slot) + ", outside 0.." + std::to_string(4 * LB_SCHEME_PARAM_VEC4S - 1));
    for (const std::string& shader : shadersOf(*s)) {
      bool found = spirvExists(shader);
      for (const std::string& o : own) found = found || o == shader;
      if (!found)
        throw InputError(where + ": scheme '" + name + "' needs shader '" + shader +
                         "', which neither the plugin nor lodbench has (list it in lodbench_add_scheme's SHADERS)");
    }
  }
}

}  // namespace

bool pluginsSupported(std::string* why) {
#if LODBENCH_PLUGINS
  (void)why;
  return true;
#else
  // The same words as CMakeLists.txt's LODBENCH_PLUGINS_OFF_REASON, which the package config shows.
  if (why)
    *why = LODBENCH_FUZZ_BUILD ? "it is a fuzzing build"
                               : "it was built with -DLODBENCH_STATIC_RUNTIME=ON (its own static C++ runtime, which a "
                                 "plugin cannot share): build lodbench without it to use plugins";
  return false;
#endif
}

const std::vector<LoadedPlugin>& loadedPlugins() {
  return registry().plugins;
}

const LoadedPlugin* pluginOfScheme(const std::string& scheme) {
  for (const LoadedPlugin& p : registry().plugins)
    for (const std::string& s : p.schemes)
      if (s == scheme) return &p;
  return nullptr;
}

const LoadedPlugin& loadPlugin(const std::string& file) {
  const std::string where = "plugin '" + printable(file, 200) + "'";
  std::string why;
  if (!pluginsSupported(&why)) throw InputError(where + ": this lodbench cannot load plugins: " + why);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw InputError(where + (std::filesystem::exists(file, ec) ? ": not a regular file" : ": no such file"));
  const std::string path = std::filesystem::canonical(file, ec).string();
  const std::string digest = sha256File(path);
  for (const LoadedPlugin& p : registry().plugins)
    if (p.path == path) {
      if (p.sha256 == digest) return p;
      throw InputError(where + ": changed on disk since it was loaded (sha256 " + p.sha256.substr(0, 8) + " -> " +
                       digest.substr(0, 8) + ")");
    }
  // RTLD_LOCAL: a plugin's own symbols stay its own; RTLD_NOW: a symbol lodbench does not export
  // fails here, not in the middle of a run.
  void* lib = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!lib) {
    const char* e = dlerror();
    throw InputError(where + ": cannot load it: " + (e ? e : "unknown error") +
                     " (a plugin may use what the installed headers declare and the C++ and Vulkan libraries)");
  }
  std::unique_ptr<void, int (*)(void*)> closeOnError(lib, dlclose);
  using Entry = const LodbenchPlugin* (*)();
  auto entry = reinterpret_cast<Entry>(dlsym(lib, "lodbench_plugin"));
  if (!entry)
    throw InputError(where +
                     ": exports no registration function lodbench_plugin (a scheme library declares it "
                     "with LODBENCH_PLUGIN(name, addSchemes) from schemes/plugin_api.h)");
  const LodbenchPlugin* p = entry();
  if (!p) throw InputError(where + ": lodbench_plugin() returned nothing");
  if (p->apiVersion != LODBENCH_PLUGIN_API_VERSION)
    throw InputError(where + " was built against " + versionText(p->apiVersion, p->lodbenchVersion) +
                     ", this lodbench speaks " + versionText(LODBENCH_PLUGIN_API_VERSION, kToolVersion) +
                     ": rebuild it against this lodbench's installed package");
  if (p->layout != pluginLayout())
    throw InputError(where + " was built against " + versionText(p->apiVersion, p->lodbenchVersion) + " with layout " +
                     std::to_string(p->layout) + ", this lodbench " + kToolVersion + " has layout " +
                     std::to_string(pluginLayout()) +
                     " (headers changed without a version bump, or another compiler or C++ library): rebuild it "
                     "against this lodbench's installed package");
  LoadedPlugin loaded{
      file, path, digest, p->apiVersion, p->name ? p->name : "", p->lodbenchVersion ? p->lodbenchVersion : "", {}};
  for (size_t i = 0; i < p->shaderCount; ++i) {
    const std::string name = p->shaders[i].name ? p->shaders[i].name : "";
    if (name.empty() || p->shaders[i].size == 0 || p->shaders[i].size % 4 != 0)
      throw InputError(where + ": shader #" + std::to_string(i + 1) + " ('" + printable(name) + "') is not SPIR-V");
    for (size_t j = 0; j < i; ++j)
      if (name == p->shaders[j].name) throw InputError(where + ": holds shader '" + name + "' twice");
    if (spirvExists(name))
      throw InputError(where + ": shader '" + name + "' has the name of " +
                       (std::filesystem::exists(shaderDir() + "/" + name) ? "a lodbench shader" : "another plugin's") +
                       "; rename its source");
  }
  PluginSchemes schemes;
  try {
    p->addSchemes(schemes);
  } catch (const std::exception& e) {
    throw InputError(where + ": adding its schemes failed: " + e.what());
  }
  if (schemes.empty()) throw InputError(where + ": adds no scheme");
  checkSchemes(where, schemes, *p);
  // Nothing can fail from here on: the plugin is registered whole or not at all.
  for (size_t i = 0; i < p->shaderCount; ++i) addSpirv(p->shaders[i].name, p->shaders[i].bytes, p->shaders[i].size);
  for (auto& s : schemes) {
    loaded.schemes.push_back(s->info().name);
    addPluginScheme(*s);
    registry().schemes.push_back(std::move(s));
  }
  closeOnError.release();  // the schemes' code lives there until the process ends
  registry().plugins.push_back(loaded);
  return registry().plugins.back();
}

}  // namespace lb
