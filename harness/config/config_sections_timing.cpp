#include <algorithm>

#include "config/config_sections.h"
#include "number_text.h"

namespace lb {

using nlohmann::json;

void parseTimingSection(const ConfigReader& r, const json& j, Config& c) {
  // Timing modes and clock-control calibration (config/timing_spec.h).
  if (j.contains("timing")) {
    const json& t = j["timing"];
    if (!t.is_array() || t.empty())
      r.fail("/timing", "expected a non-empty array of timing modes (shaded, depth, frontend)");
    c.timing.modes.clear();
    for (size_t i = 0; i < t.size(); ++i) {
      std::string m = r.string(t[i], "/timing/" + std::to_string(i));
      if (m != "shaded" && m != "depth" && m != "frontend")
        r.fail("/timing/" + std::to_string(i), "unknown timing mode '" + m + "' (shaded, depth, frontend)");
      if (std::find(c.timing.modes.begin(), c.timing.modes.end(), m) != c.timing.modes.end())
        r.fail("/timing/" + std::to_string(i), "timing mode '" + m + "' listed twice");
      c.timing.modes.push_back(m);
    }
    if (std::find(c.timing.modes.begin(), c.timing.modes.end(), "shaded") == c.timing.modes.end())
      r.fail("/timing", "must include \"shaded\" (the case's gpu_ms is the shaded time)");
  }
}

void parseCalibrationSection(const ConfigReader& r, const json& j, Config& c) {
  if (j.contains("calibration")) {
    c.timing.calibrateSet = true;
    const json& k = j["calibration"];
    if (k.is_boolean()) {
      c.timing.calibrate = k.get<bool>();
    } else {
      r.onlyKeys(k, "/calibration", {"level", "frames", "max_tries", "min_load_s"});
      c.timing.calibrate = true;
      if (k.contains("level")) c.timing.level = r.integer(k["level"], "/calibration/level", 1, 64);
      if (k.contains("frames")) c.timing.frames = r.integer(k["frames"], "/calibration/frames", 1, 1000);
      if (k.contains("min_load_s")) c.timing.minLoadS = r.number(k["min_load_s"], "/calibration/min_load_s", 0, 60);
      if (k.contains("max_tries")) c.timing.maxTries = r.integer(k["max_tries"], "/calibration/max_tries", 3, 1000);
    }
  }
}

void parseEnergySection(const ConfigReader& r, const json& j, Config& c) {
  if (!j.contains("energy")) return;
  const json& e = j["energy"];
  if (e.is_boolean()) {
    c.timing.energy = e.get<bool>();
    return;
  }
  r.onlyKeys(e, "/energy", {"window_s", "rounds"});
  c.timing.energy = true;
  if (e.contains("window_s")) c.timing.energyWindowS = r.number(e["window_s"], "/energy/window_s", 0.001, 600);
  if (e.contains("rounds")) c.timing.energyRounds = r.integer(e["rounds"], "/energy/rounds", 1, 100);
}

void parseMeasureSection(const ConfigReader& r, const json& j, Config& c) {
  if (j.contains("measure")) {
    const json& me = j["measure"];
    r.onlyKeys(me, "/measure", {"every", "passes", "diff_threshold", "compute", "flip_ppd"});
    c.measure.every = me.contains("every") ? r.integer(me["every"], "/measure/every", 0, 1000000) : 10;
    if (me.contains("passes")) {
      if (!me["passes"].is_array()) r.fail("/measure/passes", "expected an array of pass names");
      c.measure.passes.clear();
      for (size_t i = 0; i < me["passes"].size(); ++i) {
        std::string p = r.string(me["passes"][i], "/measure/passes/" + std::to_string(i));
        if (!allMeasurePasses().count(p))
          r.fail("/measure/passes/" + std::to_string(i),
                 "'" + printable(p) + "' is not one of histogram, error, image, cracks, popping, surplus");
        c.measure.passes.insert(p);
      }
    }
    if (me.contains("diff_threshold"))
      c.measure.diffThreshold = r.integer(me["diff_threshold"], "/measure/diff_threshold", 0, 255);
    if (me.contains("compute")) {
      c.measure.compute = r.string(me["compute"], "/measure/compute");
      if (c.measure.compute != "auto" && c.measure.compute != "gpu" && c.measure.compute != "cpu")
        r.fail("/measure/compute", "'" + printable(c.measure.compute) + "' is not one of auto, gpu, cpu");
    }
    if (me.contains("flip_ppd")) c.measure.flipPpd = r.number(me["flip_ppd"], "/measure/flip_ppd", 1, 1000);
  }
}

void parseMatchSection(const ConfigReader& r, const json& j, Config& c) {
  if (j.contains("match")) {
    const json& m = j["match"];
    r.onlyKeys(m, "/match", {"metric", "value", "frames", "iterations", "tune", "budget"});
    if (!m.contains("metric") || !m.contains("value")) r.fail("/match", "needs 'metric' and 'value'");
    c.match.metric = r.string(m["metric"], "/match/metric");
    if (c.match.metric != "triangles" && c.match.metric != "err_mean_px" && c.match.metric != "err_p95_px")
      r.fail("/match/metric", "'" + printable(c.match.metric) + "' is not one of triangles, err_mean_px, err_p95_px");
    c.match.value = r.number(m["value"], "/match/value", 0, 1e12);
    if (m.contains("frames")) c.match.frames = r.integer(m["frames"], "/match/frames", 1, 10000);
    if (m.contains("iterations")) c.match.iterations = r.integer(m["iterations"], "/match/iterations", 1, 60);
    if (m.contains("tune")) {
      if (!m["tune"].is_boolean()) r.fail("/match/tune", "expected true or false");
      c.match.tune = m["tune"].get<bool>();
    }
    if (m.contains("budget")) c.match.budget = r.integer(m["budget"], "/match/budget", 2, 10000);
  }
}

}  // namespace lb
