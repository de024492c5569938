#include "cli/list.h"

#include <algorithm>

#include "number_text.h"
#include "render/scheme.h"

namespace lb {

namespace {

std::string pad(const std::string& s, size_t width) {
  return s + std::string(width > s.size() ? width - s.size() : 0, ' ');
}

std::string rangeText(const ParamSpec& p) {
  return "[" + numberText(p.min) + ", " + numberText(p.max) + "]";
}

}  // namespace

std::string schemeListing(const std::vector<const Scheme*>& schemes) {
  size_t nameW = 0, paramW = 0, defaultW = 0, rangeW = 0;
  bool anyInteger = false;
  for (const Scheme* s : schemes) {
    const SchemeInfo& i = s->info();
    nameW = std::max(nameW, i.name.size());
    for (const ParamSpec& p : i.params) {
      paramW = std::max(paramW, p.name.size());
      defaultW = std::max(defaultW, numberText(p.defaultValue).size());
      rangeW = std::max(rangeW, rangeText(p).size());
      anyInteger = anyInteger || p.integer;
    }
  }
  const std::string indent(nameW + 2, ' ');
  std::string out;
  for (const Scheme* s : schemes) {
    const SchemeInfo& i = s->info();
    out += pad(i.name, nameW + 2) + i.description + "\n";
    out += indent + "seed: " + i.seed + "\n";
    out +=
        indent + "patches: " + topologyName(i.topology) + ", partitioning: " + partitioningName(i.partitioning) + "\n";
    for (const ParamSpec& p : i.params) {
      std::string line = indent + pad(p.name, paramW) + "  default " + pad(numberText(p.defaultValue), defaultW) +
                         "  range " + pad(rangeText(p), rangeW);
      if (anyInteger) line += p.integer ? "  integer" : "         ";
      line += "  " + p.help;
      out += line + "\n";
    }
  }
  return out;
}

}  // namespace lb
