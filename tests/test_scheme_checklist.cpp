// What a scheme truly needs besides its own schemes/<name>.cpp (its shaders, its line in the
// registry, a README row, its cases in the CI config and baseline), checked for every registered
// scheme. README's "Adding a scheme" lists the same: a scheme missing any of them fails here with
// the whole list of what is missing, not one item per run. Lists that grow with every scheme
// (configs' scheme lists, chart colours) are derived from the registry, so they ask for nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "config/config.h"
#include "metrics/frame_metrics.h"
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

std::vector<std::string> missingFor(const Scheme& scheme, const std::set<std::string>& ci,
                                    const std::set<std::string>& baseline, const std::string& readme) {
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
  // Mesh shaders: the task shader, which decides the LOD or reads the twin's (its parameter header).
  const bool taskStage = info.path == DrawPath::Mesh;
  std::string stem = taskStage ? info.task : vertexStage ? info.vert : info.tesc;
  const std::string lodShader = stem + (taskStage ? ".task" : vertexStage ? ".vert" : ".tesc");
  const std::string tesc = "shaders/" + lodShader;
  need(!stem.empty() && exists(tesc), tesc);
  if (!info.compute.empty()) need(exists("shaders/" + info.compute + ".comp"), "shaders/" + info.compute + ".comp");
  if (!info.params.empty()) {
    // The slots come from a parameter header the LOD shader includes (directly or through a .glsl):
    // its own shaders/<stem>_params.h, or the one of the scheme it shares a rule with (cbt-ts takes
    // cbt's).
    std::set<std::string> seen;
    const std::string text = shaderWithIncludes(lodShader, seen);
    static const std::regex paramsInclude(R"re(#include\s+"([a-z0-9_]+_params\.h)")re");
    std::map<std::string, std::string> slots;
    for (std::sregex_iterator it(text.begin(), text.end(), paramsInclude), end; it != end; ++it)
      for (auto& [k, v] : defines((*it)[1])) slots[k] = v;
    need(!slots.empty(), tesc + ": #include \"" + stem + "_params.h\" (its parameter slots)");
    for (const ParamSpec& p : info.params) {
      bool found = false;
      for (auto& [macro, value] : slots)
        found =
            found || (macro.size() > p.name.size() + 1 && macro.rfind("LB_", 0) == 0 &&
                      macro.compare(macro.size() - p.name.size() - 1, std::string::npos, "_" + upper(p.name)) == 0 &&
                      value == std::to_string(p.slot));
      need(found, "shaders/" + stem + "_params.h: #define LB_" + upper(stem) + "_" + upper(p.name) + " " +
                      std::to_string(p.slot) + " (included by " + tesc + ")");
    }
  }
  // The main parameter names a parameter, and the default job's front sweeps it over several values.
  const ParamSpec* main = nullptr;
  for (const ParamSpec& p : info.params)
    if (p.name == info.mainParam) main = &p;
  need(info.mainParam.empty() || main,
       "schemes/" + info.name + ".cpp: mainParam '" + info.mainParam + "' is not one of its parameters");
  if (main) {
    bool inRange = info.front.size() >= 2;
    for (double v : info.front) inRange = inRange && v >= main->min && v <= main->max;
    need(inRange, "schemes/" + info.name + ".cpp: .front = {several values of " + info.mainParam + " in its range}");
  }
  need(ci.count(info.name) > 0, "configs/ci.json: its cases (\"all\" takes every scheme)");
  need(baseline.count(info.name) > 0, "results/baseline/ci: its cases (bash scripts/refresh-baseline.sh)");
  need(readme.find("\n| `" + info.name + "` |") != std::string::npos, "README.md: a row in the Schemes table");
  return missing;
}

TEST(SchemeChecklist, EverySchemeHasEveryFileItNeeds) {
  std::set<std::string> ci, baseline;
  for (const SchemeEntry& e : loadConfig(kRoot + "/configs/ci.json").schemes) ci.insert(e.name);
  for (const auto& f : std::filesystem::directory_iterator(kRoot + "/results/baseline/ci/r1/cases"))
    baseline.insert(f.path().filename().string().substr(0, f.path().filename().string().find('_')));
  const std::string readme = readText(kRoot + "/README.md");
  std::string report;
  for (const Scheme* s : allSchemes())
    for (const std::string& m : missingFor(*s, ci, baseline, readme)) report += "\n  " + s->info().name + ": " + m;
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
