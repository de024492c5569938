#include "config/case_identity.h"

#include "config/config.h"
#include "schemes/plugins.h"
#include "sha256.h"
#include "terrain/generators.h"
#include "terrain/heightfield.h"
#include "version.h"

namespace lb {

using nlohmann::json;

static std::string fileDigest(const std::string& file, FileDigests& files) {
  auto it = files.find(file);
  if (it != files.end()) return it->second;
  return files[file] = sha256File(file);
}

json terrainInputs(const TerrainSpec& t, FileDigests& files) {
  json j = {
      {"type", t.type}, {"extent", t.extent}, {"height_scale", t.heightScale}, {"origin", {t.originX, t.originZ}}};
  if (t.type == "procedural" || isGeneratedTerrain(t.type)) {
    j["size"] = t.size;
    j["seed"] = t.seed;
    j["detail"] = t.detailToSpacing ? "resolution" : "fixed";
  } else {
    j["sha256"] = fileDigest(t.file, files);
    if (t.type == "r16" || t.type == "r32f") j["raw_size"] = {t.rawWidth, t.rawHeight};
    if (t.type == "gdal") {  // what of the file is read
      j["band"] = t.band;
      j["window"] = t.window.empty() ? nlohmann::json(nullptr) : nlohmann::json(t.window);
      j["overview"] = t.overview;
    }
  }
  if (t.page > 0) j["page"] = t.page;  // named only when paged, so digests of earlier sweeps still match
  return j;
}

json pathInputs(const std::string& path, FileDigests& files) {
  return {{"sha256", fileDigest(path, files)}};
}

json measurementInputs(const Config& c) {
  json passes = json::array();
  for (auto& p : c.measure.passes) passes.push_back(p);
  json measure = {{"every", c.measure.every}, {"passes", passes}, {"diff_threshold", c.measure.diffThreshold}};
  // Named only when not the default, so digests of earlier sweeps still match.
  if (c.measure.compute != "auto") measure["compute"] = c.measure.compute;
  if (c.measure.flipPpd != LB_FLIP_DEFAULT_PPD) measure["flip_ppd"] = c.measure.flipPpd;
  json j = {{"grid", c.grid},
            {"fps", c.fps},
            {"warmup_frames", c.warmupFrames},
            {"max_frames", c.maxFrames},
            {"repetitions", c.repetitions},
            {"measure", measure},
            {"images",
             {{"frames", c.images.frames},
              {"modes", c.images.modes},
              {"resolution", {c.images.width, c.images.height}},
              {"worst", c.images.worst}}},
            {"timing", {{"modes", c.timing.modes}}}};
  // Since a config that grows resumes its folder (only the digests guard it), every setting that
  // shapes a case's records is here, defaults included.
  // Unset, calibration runs on every device but a CPU rasterizer: "when" says which rule applied.
  if (c.timing.calibrate || !c.timing.calibrateSet)
    j["timing"]["calibration"] = {
        {"level", c.timing.level},
        {"frames", c.timing.frames},
        {"max_tries", c.timing.maxTries},
        {"tolerance", c.timing.tolerance},
        {"drift_limit", c.timing.driftLimit},
        {"min_load_s", c.timing.minLoadS},
        {"when", c.timing.calibrateSet ? "always" : "on a device that is not a CPU rasterizer"}};
  // Energy windows (replay/energy_pass.h): named only when not the default, so digests of earlier
  // sweeps still match.
  const TimingSpec defaults;
  if (!c.timing.energy)
    j["timing"]["energy"] = false;
  else if (c.timing.energyWindowS != defaults.energyWindowS || c.timing.energyRounds != defaults.energyRounds)
    j["timing"]["energy"] = {{"window_s", c.timing.energyWindowS}, {"rounds", c.timing.energyRounds}};
  if (c.match.on()) {
    j["match"] = {{"metric", c.match.metric},
                  {"value", c.match.value},
                  {"frames", c.match.frames},
                  {"iterations", c.match.iterations}};
    if (c.match.budget > 0) j["match"]["budget"] = c.match.budget;  // named only when set: earlier digests hold
  }
  if (c.interleave) j["interleave"] = true;  // named only when on: earlier digests hold
  if (c.timing.testDrift != 0) j["timing"]["test_drift"] = c.timing.testDrift;  // tests: a planted drift
  if (c.testSlowdown > 0) j["test_slowdown"] = c.testSlowdown;  // a planted slowdown changes the timings
  return j;
}

json caseInputs(const json& terrain, const json& path, int width, int height, const std::string& scheme,
                const json& params, const json& measurement) {
  json j = {{"tool_version", kToolVersion}, {"scheme", scheme}, {"params", params},
            {"terrain", terrain},           {"path", path},     {"resolution", {width, height}},
            {"measurement", measurement}};
  // A plugin's scheme is its library: a rebuilt one (its code or its shaders) is another scheme.
  // Named only for plugins, so the digests of built-in schemes' cases hold.
  if (const LoadedPlugin* p = pluginOfScheme(scheme))
    j["plugin"] = {{"sha256", p->sha256}, {"api_version", p->apiVersion}, {"name", p->name}};
  return j;
}

// nlohmann::json keeps object keys sorted and prints doubles round-trip exactly, so the dump is a
// canonical form.
std::string inputsDigest(const json& inputs) {
  return sha256Hex(inputs.dump());
}

static std::string brief(const json& v) {
  if (v.is_string() && v.get<std::string>().size() == 64) return v.get<std::string>().substr(0, 8);
  std::string s = v.dump();
  return s.size() > 60 ? s.substr(0, 57) + "..." : s;
}

static void diff(const json& a, const json& b, const std::string& at, std::string& out) {
  if (a == b) return;
  if (a.is_object() && b.is_object()) {
    for (auto& [k, v] : a.items()) diff(v, b.contains(k) ? b[k] : json(), at.empty() ? k : at + "." + k, out);
    for (auto& [k, v] : b.items())
      if (!a.contains(k)) diff(json(), v, at.empty() ? k : at + "." + k, out);
    return;
  }
  std::string name = at;
  if (name.size() > 7 && name.compare(name.size() - 7, 7, ".sha256") == 0)
    name = name.substr(0, name.size() - 7) + " file contents (sha256 ";
  else
    name += " (";
  if (!out.empty()) out += "; ";
  out += name + (a.is_null() ? "absent" : brief(a)) + " -> " + (b.is_null() ? "absent" : brief(b)) + ")";
}

std::string describeInputChange(const json& recorded, const json& now) {
  std::string out;
  diff(recorded, now, "", out);
  return out;
}

}  // namespace lb
