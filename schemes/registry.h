#pragma once
// The one explicit table of LOD schemes. The CLI, tests and benchmarks all iterate it; schemes of
// plugins (schemes/plugins.h) join it after the built-in ones.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "render/scheme.h"

namespace lb {

const std::vector<const Scheme*>& allSchemes();
// Appends a plugin's scheme to allSchemes(); schemes/plugins.cpp checks its name is free first.
// Plugins are never unloaded, so the scheme lives as long as the process.
void addPluginScheme(const Scheme& scheme);
// Control schemes (schemes/controls.cpp): twins of a compared scheme with a known cost ratio, for
// checking the verdict. findScheme finds them; allSchemes and "all" leave them out.
const std::vector<const Scheme*>& controlSchemes();
// nullptr when unknown.
const Scheme* findScheme(const std::string& name);
std::string schemeNames();  // "a, b, c" for error messages
// "unknown scheme 'sphre' (known: a, b, c); did you mean 'sphere'?" (the suggestion when one is close).
std::string unknownSchemeText(const std::string& name);
// The settings a user of a scheme tunes besides its main parameter, each with the values a tuned
// matched search tries (replay/matched.h tuneAndMatch): "grid" is the tessellation grid (patches
// per side), any other key a parameter of the scheme. Empty for a scheme with nothing else to tune.
using TuneSpace = std::map<std::string, std::vector<double>>;
TuneSpace defaultTuneSpace(const Scheme& scheme);

// Schemes a config names at once (config/config.h): "all" is allSchemes() (plugins' included, no
// control); "tessellation", "instanced-grid", "gpu-indirect" and "mesh" those of one draw path;
// "controls" the controls. Registry order; empty for a name that is no group.
std::vector<const Scheme*> schemeGroup(const std::string& group);
const std::vector<std::string>& schemeGroupNames();

// The first registered scheme whose main parameter plays `role`; nullptr when none does.
const Scheme* schemeWithRole(MainParamRole role);

}  // namespace lb
