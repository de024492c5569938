#include "render/scheme.h"

#include <cassert>
#include <cmath>
#include <sstream>
#include <utility>

#include "did_you_mean.h"
#include "error.h"
#include "number_text.h"
#include "shaders/shared.h"

namespace lb {

void Scheme::update(FrameUniforms& frame, const ParamValues& values) const {
  for (const ParamSpec& p : info().params) {
    assert(p.slot >= 0 && p.slot < LB_SCHEME_PARAM_VEC4S * 4);
    frame.params[p.slot / 4][p.slot % 4] = float(values.at(p.name));
  }
}

Partitioning Scheme::partitioning(const ParamValues& values) const {
  auto it = values.find(kIntegerParam);
  return it != values.end() && it->second != 0 ? Partitioning::Integer : info().partitioning;
}

double Scheme::targetAreaPx(const ParamValues& values) const {
  if (info().mainParamRole != MainParamRole::TriangleWidthPx) return 0.0;
  auto it = values.find(info().mainParam);
  return it == values.end() ? 0.0 : 0.5 * it->second * it->second;
}

ParamValues resolveParams(const SchemeInfo& info, const ParamValues& given) {
  ParamValues out;
  for (auto& p : info.params) out[p.name] = p.defaultValue;
  for (auto& [name, value] : given) {
    const ParamSpec* spec = nullptr;
    for (auto& p : info.params)
      if (p.name == name) spec = &p;
    if (!spec) {
      std::string known;
      std::vector<std::string> names;
      for (auto& p : info.params) {
        known += (known.empty() ? "" : ", ") + p.name;
        names.push_back(p.name);
      }
      throw InputError("scheme '" + info.name + "' has no parameter '" + name +
                       "' (parameters: " + (known.empty() ? "none" : known) + ")" + didYouMean(name, names));
    }
    if (!std::isfinite(value) || value < spec->min || value > spec->max)
      throw InputError("scheme '" + info.name + "' parameter '" + name + "' = " + numberText(value) + " is outside [" +
                       numberText(spec->min) + ", " + numberText(spec->max) + "]");
    if (spec->integer && value != std::floor(value))
      throw InputError("scheme '" + info.name + "' parameter '" + name + "' must be an integer");
    out[name] = value;
  }
  return out;
}

void requireOrdered(const std::string& scheme, const ParamValues& values, const std::string& lo, const std::string& hi,
                    bool strict) {
  double a = values.at(lo), b = values.at(hi);
  if (strict ? a < b : a <= b) return;
  throw InputError("scheme '" + scheme + "': " + hi + " (" + numberText(b) + ") must be " +
                   (strict ? "greater than " : "at least ") + lo + " (" + numberText(a) + ")");
}

SchemeTexture redTexture(int width, int height, std::vector<float> red) {
  return {width, height, std::move(red), 1};
}

const char* partitioningName(Partitioning p) {
  switch (p) {
    case Partitioning::Integer:
      return "integer";
    case Partitioning::FractionalEven:
      return "fractional_even";
    case Partitioning::FractionalOdd:
      return "fractional_odd";
  }
  return "?";
}

bool drawsPatchGrid(const SchemeInfo& info) {
  return info.path == DrawPath::Tessellation || (info.path == DrawPath::Mesh && info.meshLod == DrawPath::Tessellation);
}

const char* topologyName(Topology t) {
  switch (t) {
    case Topology::Quad4:
      return "quad4";
    case Topology::Quad12:
      return "quad12";
    case Topology::Tri3:
      return "tri3";
  }
  return "?";
}

}  // namespace lb
