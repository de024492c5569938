// The files a scheme needs besides its own schemes/<name>.cpp, checked for every registered scheme.
// README's "Adding a scheme" lists the same files: a scheme missing any of them fails here with
// the whole list of what is missing, not one item per run.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "metrics/frame_metrics.h"
#include "report/charts.h"
#include "schemes/registry.h"

using namespace lb;

namespace {

const std::string kRoot = LODBENCH_SOURCE_DIR;

std::string readText(const std::string& path) {
  std::ifstream in(path);
  if (!in) return {};
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

bool exists(const std::string& path) {
  return bool(std::ifstream(kRoot + "/" + path));
}

// A shader's text with the text of every shaders/*.glsl it includes, recursively.
std::string shaderWithIncludes(const std::string& file, std::set<std::string>& seen) {
  if (!seen.insert(file).second) return {};
  std::string text = readText(kRoot + "/shaders/" + file), all = text;
  static const std::regex include(R"re(#include\s+"([A-Za-z0-9_]+\.glsl)")re");
  for (std::sregex_iterator it(text.begin(), text.end(), include), end; it != end; ++it)
    all += shaderWithIncludes((*it)[1], seen);
  return all;
}

// `#define NAME value` lines of shaders/<header> and the shaders/*.h it includes, each value
// followed through other such names (LB_PLANEFIT_DMIN is LB_DISTANCE_DMIN).
std::map<std::string, std::string> defines(const std::string& header) {
  std::map<std::string, std::string> out;
  std::vector<std::string> queue{header};
  static const std::regex define(R"re(#define[ \t]+([A-Z0-9_]+)[ \t]+([^\s]+))re");
  static const std::regex include(R"re(#include\s+"([A-Za-z0-9_]+\.h)")re");
  for (size_t i = 0; i < queue.size() && i < 16; ++i) {
    std::string text = readText(kRoot + "/shaders/" + queue[i]);
    for (std::sregex_iterator it(text.begin(), text.end(), define), end; it != end; ++it) out[(*it)[1]] = (*it)[2];
    for (std::sregex_iterator it(text.begin(), text.end(), include), end; it != end; ++it) queue.push_back((*it)[1]);
  }
  for (auto& [name, value] : out)
    for (int hop = 0; hop < 8 && out.count(value); ++hop) value = out[value];
  return out;
}

std::string upper(std::string s) {
  for (char& c : s) c = c == '-' ? '_' : char(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

const nlohmann::json* configEntry(const nlohmann::json& config, const std::string& scheme) {
  for (const auto& s : config["schemes"])
    if (s.value("name", "") == scheme) return &s;
  return nullptr;
}

std::vector<std::string> missingFor(const Scheme& scheme, const nlohmann::json& quick, const nlohmann::json& ci,
                                    const std::string& readme) {
  const SchemeInfo& info = scheme.info();
  std::vector<std::string> missing;
  auto need = [&](bool ok, const std::string& what) {
    if (!ok) missing.push_back(what);
  };
  // Shaders, and the parameter header they share with the C++ side: the LOD shader is the control
  // shader on the tessellation path and the vertex shader on the instanced one.
  // GPU-indirect: the shader that places the records' triangles (the control shader of a patch
  // footprint, else the vertex shader), which includes the parameter header its tree shares (cbt-ts
  // takes cbt's: cbt_params.h).
  const bool instanced = info.path == DrawPath::InstancedGrid;
  const bool indirect = info.path == DrawPath::GpuIndirect;
  const bool vertexStage = instanced || (indirect && info.tesc.empty());
  std::string stem = vertexStage ? info.vert : info.tesc;
  const std::string lodShader = stem + (vertexStage ? ".vert" : ".tesc");
  const std::string tesc = "shaders/" + lodShader;
  need(!stem.empty() && exists(tesc), tesc);
  if (indirect && exists(tesc)) {
    std::smatch m;
    const std::string text = readText(kRoot + "/" + tesc);
    if (std::regex_search(text, m, std::regex("#include \"([a-z0-9_]+)_params\\.h\""))) stem = m[1];
  }
  if (!info.compute.empty()) need(exists("shaders/" + info.compute + ".comp"), "shaders/" + info.compute + ".comp");
  if (!info.params.empty()) {
    const std::string header = stem + "_params.h";
    auto slots = defines(header);
    need(!slots.empty(), "shaders/" + header + " (its parameter slots)");
    for (const ParamSpec& p : info.params) {
      const std::string macro = "LB_" + upper(stem) + "_" + upper(p.name);
      need(slots.count(macro) && slots[macro] == std::to_string(p.slot),
           "shaders/" + header + ": #define " + macro + " " + std::to_string(p.slot));
    }
    std::set<std::string> seen;
    need(shaderWithIncludes(lodShader, seen).find("#include \"" + header + "\"") != std::string::npos,
         tesc + ": #include \"" + header + "\" (directly or through a .glsl it includes)");
  }
  // The main parameter names a parameter; the default job sweeps it (a front needs several values).
  bool mainDeclared = info.mainParam.empty();
  for (const ParamSpec& p : info.params) mainDeclared = mainDeclared || p.name == info.mainParam;
  need(mainDeclared, "schemes/" + info.name + ".cpp: mainParam '" + info.mainParam + "' is not one of its parameters");
  if (!info.mainParam.empty()) {
    const nlohmann::json* q = configEntry(quick, info.name);
    bool swept = q && q->contains("params") && (*q)["params"].contains(info.mainParam) &&
                 (*q)["params"][info.mainParam].is_array() && (*q)["params"][info.mainParam].size() >= 2;
    need(swept, "configs/quick.json: {\"name\": \"" + info.name + "\", \"params\": {\"" + info.mainParam +
                    "\": [several values]}}");
  }
  need(configEntry(ci, info.name) != nullptr,
       "configs/ci.json: {\"name\": \"" + info.name + "\"} (then bash scripts/refresh-baseline.sh)");
  bool styled = false;
  for (const SchemeStyle& s : schemeStyles()) styled = styled || info.name == s.scheme;
  need(styled, "harness/report/charts_style.cpp: a colour and point shape in schemeStyles()");
  need(readme.find("\n| `" + info.name + "` |") != std::string::npos, "README.md: a row in the Schemes table");
  return missing;
}

TEST(SchemeChecklist, EverySchemeHasEveryFileItNeeds) {
  const nlohmann::json quick = nlohmann::json::parse(readText(kRoot + "/configs/quick.json"));
  const nlohmann::json ci = nlohmann::json::parse(readText(kRoot + "/configs/ci.json"));
  const std::string readme = readText(kRoot + "/README.md");
  std::string report;
  for (const Scheme* s : allSchemes())
    for (const std::string& m : missingFor(*s, quick, ci, readme)) report += "\n  " + s->info().name + ": " + m;
  EXPECT_TRUE(report.empty()) << "missing (README.md, \"Adding a scheme\"):" << report;
}

// Roles the harness looks schemes up by: the surplus metric needs one error-bounded scheme,
// calibration and probes one scheme whose main parameter is a uniform level.
TEST(SchemeChecklist, RolesTheHarnessLooksUpAreTaken) {
  for (MainParamRole role : {MainParamRole::ErrorBoundPx, MainParamRole::UniformLevel}) {
    int n = 0;
    for (const Scheme* s : allSchemes()) n += s->info().mainParamRole == role && !s->info().mainParam.empty();
    EXPECT_EQ(n, 1) << "role " << int(role);
  }
}

// A scheme's own counters become frame metrics and CSV columns beside everyone's: names must not clash.
TEST(SchemeChecklist, CounterKeysAreUnique) {
  std::vector<std::string> columns = metricColumns();
  std::set<std::string> keys(columns.begin(), columns.end());
  EXPECT_EQ(keys.size(), columns.size());
  for (const Scheme* s : allSchemes())
    for (const SchemeCounter& c : s->info().counters) EXPECT_TRUE(keys.insert(c.caseKey).second) << c.caseKey;
}

}  // namespace
