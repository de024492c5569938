#pragma once
// The one explicit table of LOD schemes. The CLI, tests and benchmarks all iterate it.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "render/scheme.h"

namespace lb {

const std::vector<const Scheme*>& allSchemes();
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

// The first registered scheme whose main parameter plays `role`; nullptr when none does.
const Scheme* schemeWithRole(MainParamRole role);

}  // namespace lb
