#include "config/config_sections.h"

#include <algorithm>

#include "camera/camera_path.h"
#include "error.h"
#include "number_text.h"

namespace lb {

using nlohmann::json;

void parseNameSection(const ConfigReader& r, const json& j, Config& c) {
  if (j.contains("name")) c.name = r.string(j["name"], "/name");
  if (c.name.empty() || c.name.find_first_of("/\\ ") != std::string::npos)
    r.fail("/name", "must be a non-empty name without '/', '\\' or spaces");
  if (j.contains("device")) c.device = r.string(j["device"], "/device");
  if (!c.device.empty()) c.deviceWhere = configField(c, "/device");
}

void parseResolutionSection(const ConfigReader& r, const json& j, Config& c) {
  for (const char* key : {"resolution", "resolutions"}) {
    if (!j.contains(key)) continue;
    const json& v = j[key];
    std::string ptr = std::string("/") + key;
    auto pair = [&](const json& p, const std::string& pp) {
      if (!p.is_array() || p.size() != 2) r.fail(pp, "expected [width, height]");
      int w = r.integer(p[0], pp + "/0", 16, 8192);
      int h = r.integer(p[1], pp + "/1", 16, 8192);
      return std::make_pair(w, h);
    };
    c.resolutions.clear();
    if (v.is_array() && !v.empty() && v[0].is_array()) {
      for (size_t i = 0; i < v.size(); ++i) c.resolutions.push_back(pair(v[i], ptr + "/" + std::to_string(i)));
    } else {
      c.resolutions.push_back(pair(v, ptr));
    }
  }
}

void parseGridSection(const ConfigReader& r, const json& j, Config& c) {
  if (j.contains("grid") && j.contains("grids")) r.fail("/grids", "give either grid or grids, not both");
  if (j.contains("grid")) c.grid = r.integer(j["grid"], "/grid", 1, 1024);
  c.grids = {c.grid};
  if (j.contains("grids")) {
    const json& g = j["grids"];
    if (!g.is_array() || g.empty()) r.fail("/grids", "expected a non-empty list of patch counts per side");
    c.grids.clear();
    for (size_t i = 0; i < g.size(); ++i) {
      std::string at = "/grids/" + std::to_string(i);
      c.grids.push_back(r.integer(g[i], at, 1, 1024));
      if (std::count(c.grids.begin(), c.grids.end(), c.grids.back()) > 1) r.fail(at, "grid listed twice; remove one");
    }
    c.grid = c.grids.front();
  }
}

void parseFrameSection(const ConfigReader& r, const json& j, Config& c) {
  if (j.contains("fps")) c.fps = r.number(j["fps"], "/fps", 1, 1000);
  if (j.contains("warmup_frames")) c.warmupFrames = r.integer(j["warmup_frames"], "/warmup_frames", 0, 100000);
  if (j.contains("max_frames")) c.maxFrames = r.integer(j["max_frames"], "/max_frames", 0, 10000000);
  if (j.contains("case_timeout_s")) c.caseTimeoutS = r.number(j["case_timeout_s"], "/case_timeout_s", 0, 1e7);
  if (j.contains("repetitions")) c.repetitions = r.integer(j["repetitions"], "/repetitions", 1, 1000);
  if (j.contains("interleave")) {
    if (!j["interleave"].is_boolean()) r.fail("/interleave", "expected true or false");
    c.interleave = j["interleave"].get<bool>();
  }
}

std::vector<int> parsePathSection(const ConfigReader& r, const json& j, const std::string& baseDir, Config& c) {
  std::vector<int> pathFrames;  // frames each path gives at this fps and max_frames
  auto addPath = [&](const json& p, const std::string& ptr) {
    std::string path = inputFile(r, p, ptr, baseDir, "camera path");
    // Parse it now: a malformed CSV stops the run before any case (with the CSV's own line).
    try {
      int frames = frameCount(loadCameraPath(path), c.fps);
      pathFrames.push_back(c.maxFrames > 0 ? std::min(frames, c.maxFrames) : frames);
    } catch (const InputError& e) {
      r.fail(ptr, e.what());
    }
    c.paths.push_back(path);
    c.pathFields.push_back(ptr);
  };
  if (j.contains("path")) addPath(j["path"], "/path");
  if (j.contains("paths")) {
    if (!j["paths"].is_array() || j["paths"].empty())
      r.fail("/paths", "expected a non-empty array of CSV files (or leave 'paths' out)");
    for (size_t i = 0; i < j["paths"].size(); ++i) addPath(j["paths"][i], "/paths/" + std::to_string(i));
  }
  if (c.paths.empty()) r.fail("", "no camera path: set 'paths' to a list of CSV files");
  return pathFrames;
}

// images.frames: each frame must lie on every path (a frame past a path's end would be silently
// left out of that path's cases).
static void parseImageFrames(const ConfigReader& r, const json& frames, const std::vector<int>& pathFrames, Config& c) {
  if (!frames.is_array()) r.fail("/images/frames", "expected an array of frame indices");
  for (size_t i = 0; i < frames.size(); ++i) {
    const std::string ptr = "/images/frames/" + std::to_string(i);
    int f = r.integer(frames[i], ptr, -1000000, 1000000);
    for (size_t k = 0; k < pathFrames.size(); ++k)
      if (f >= pathFrames[k] || f < -pathFrames[k])
        r.fail(ptr, std::to_string(f) + " is outside the " + std::to_string(pathFrames[k]) + " frames of '" +
                        c.paths[k] + "' (valid: 0.." + std::to_string(pathFrames[k] - 1) + ", or -1..-" +
                        std::to_string(pathFrames[k]) + " from the end)");
    c.images.frames.push_back(f);
  }
}

static void parseImageModes(const ConfigReader& r, const json& modes, Config& c) {
  c.images.modes.clear();
  if (!modes.is_array()) r.fail("/images/modes", "expected an array of image modes");
  for (size_t i = 0; i < modes.size(); ++i) {
    std::string m = r.string(modes[i], "/images/modes/" + std::to_string(i));
    if (m != "shaded" && m != "heatmap" && m != "wireframe" && m != "error" && m != "cracks" && m != "flip")
      r.fail("/images/modes/" + std::to_string(i),
             "'" + printable(m) + "' is not one of shaded, heatmap, wireframe, error, cracks, flip");
    c.images.modes.push_back(m);
  }
}

void parseImageSection(const ConfigReader& r, const json& j, const std::vector<int>& pathFrames, Config& c) {
  if (!j.contains("images")) return;
  const json& im = j["images"];
  r.onlyKeys(im, "/images", {"frames", "modes", "resolution", "worst"});
  if (im.contains("resolution")) {
    const json& v = im["resolution"];
    if (!v.is_array() || v.size() != 2) r.fail("/images/resolution", "expected [width, height]");
    c.images.width = r.integer(v[0], "/images/resolution/0", 16, 8192);
    c.images.height = r.integer(v[1], "/images/resolution/1", 16, 8192);
  }
  if (im.contains("worst")) {
    if (!im["worst"].is_boolean()) r.fail("/images/worst", "expected true or false");
    c.images.worst = im["worst"].get<bool>();
  }
  if (im.contains("frames")) parseImageFrames(r, im["frames"], pathFrames, c);
  c.images.modes = {"shaded"};
  if (im.contains("modes")) parseImageModes(r, im["modes"], c);
}

}  // namespace lb
