#include "schemes/registry.h"

#include "did_you_mean.h"

namespace lb {

// Each scheme file defines one factory; adding a scheme = one line here.
const Scheme& uniformScheme();
const Scheme& sphereScheme();
const Scheme& interlockScheme();
const Scheme& sphereRingsScheme();
const Scheme& densityScheme();
const Scheme& phongScheme();
const Scheme& distanceScheme();
const Scheme& referenceScheme();
const Scheme& planeFitScheme();
const Scheme& errBoundScheme();
const Scheme& sphereEdgeScheme();
const Scheme& cdlodScheme();
const Scheme& cdlodSseScheme();
const Scheme& clipmapScheme();
const Scheme& cbtScheme();
const Scheme& cbtTsScheme();

const std::vector<const Scheme*>& allSchemes() {
  static const std::vector<const Scheme*> schemes = {
      &uniformScheme(),  &sphereScheme(),   &interlockScheme(),  &sphereRingsScheme(),
      &densityScheme(),  &phongScheme(),    &distanceScheme(),   &referenceScheme(),
      &planeFitScheme(), &errBoundScheme(), &sphereEdgeScheme(), &cdlodScheme(),
      &cdlodSseScheme(), &clipmapScheme(),  &cbtScheme(),        &cbtTsScheme(),
  };
  return schemes;
}

const Scheme* findScheme(const std::string& name) {
  for (const Scheme* s : allSchemes())
    if (s->info().name == name) return s;
  return nullptr;
}

const Scheme* schemeWithRole(MainParamRole role) {
  for (const Scheme* s : allSchemes())
    if (s->info().mainParamRole == role && !s->info().mainParam.empty()) return s;
  return nullptr;
}

std::string schemeNames() {
  std::string out;
  for (const Scheme* s : allSchemes()) out += (out.empty() ? "" : ", ") + s->info().name;
  return out;
}

std::string unknownSchemeText(const std::string& name) {
  std::vector<std::string> names;
  for (const Scheme* s : allSchemes()) names.push_back(s->info().name);
  return "unknown scheme '" + name + "' (known: " + schemeNames() + ")" + didYouMean(name, names);
}

}  // namespace lb
