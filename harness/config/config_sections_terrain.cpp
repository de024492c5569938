#include "config/config_sections.h"

#include <set>

#include "error.h"
#include "number_text.h"
#include "terrain/gdal_loader.h"
#include "terrain/generators.h"
#include "terrain/terrain_cache.h"

namespace lb {

using nlohmann::json;

static std::vector<TerrainSpec> parseTerrain(const ConfigReader& r, const json& t, const std::string& ptr, const std::string& base) {
  r.onlyKeys(t, ptr, {"type", "file", "size", "seed", "extent", "height_scale", "width", "height", "origin", "band",
                      "window", "overview", "detail"});
  TerrainSpec spec;
  if (t.contains("type")) spec.type = r.string(t["type"], ptr + "/type");
  static const std::set<std::string> kTypes = {"procedural", "hgt",   "png16", "r16",  "r32f",
                                               "gdal",       "spikes", "cliff", "flat", "voids"};
  if (!kTypes.count(spec.type))
    r.fail(ptr + "/type", "'" + printable(spec.type) +
                              "' is not one of procedural, hgt, png16, r16, r32f, gdal, spikes, cliff, flat, voids");
  const bool gdal = spec.type == "gdal";
  if (gdal && !haveGdal())
    r.fail(ptr + "/type", "this build has no GDAL (configured with -DLODBENCH_GDAL=OFF, the default with "
                          "LODBENCH_STATIC_RUNTIME): build with GDAL, or convert the DEM to r32f");
  // A field the type does not read would be silently ignored: reject it instead.
  const bool raw = spec.type == "r16" || spec.type == "r32f", procedural = spec.type == "procedural" || isGeneratedTerrain(spec.type);
  auto reason = [](const std::string& k) {
    if (k == "file") return "generated terrains are not read from a file";
    if (k == "size" || k == "seed") return "only generated terrains take a size and seed";
    if (k == "band" || k == "window" || k == "overview") return "only gdal rasters take a band, window and overview";
    return "only r16 and r32f take a width and height; other files carry their size";
  };
  for (const std::string k : {"file", "size", "seed", "width", "height", "band", "window", "overview"}) {
    const bool used = k == "file"                    ? !procedural
                      : (k == "size" || k == "seed") ? procedural
                      : (k == "width" || k == "height") ? raw
                                                        : gdal;
    if (t.contains(k) && !used) r.fail(ptr + "/" + k, "terrain type '" + spec.type + "' does not use '" + k + "' (" + reason(k) + ")");
  }
  if (!procedural) {
    if (!t.contains("file")) r.fail(ptr, "terrain type '" + spec.type + "' needs a 'file'");
    spec.file = inputFile(r, t["file"], ptr + "/file", base, "heightmap file");
    spec.heightScale = 1.0f;
  }
  if (spec.type == "voids") spec.heightScale = 1.0f;  // an SRTM tile: metres, like hgt files
  if (gdal) spec.extent = 0.0f;  // from the file's georeferencing unless "extent" is given
  if (t.contains("size")) spec.size = r.integer(t["size"], ptr + "/size", 2, 16385);
  if (t.contains("detail")) {  // procedural only: "fixed" (8 octaves, the default) or "resolution"
    if (spec.type != "procedural") r.fail(ptr + "/detail", "only procedural terrains take a 'detail'");
    const std::string d = r.string(t["detail"], ptr + "/detail");
    if (d != "fixed" && d != "resolution") r.fail(ptr + "/detail", "'" + printable(d) + "' is not one of fixed, resolution");
    spec.detailToSpacing = d == "resolution";
  }
  if (t.contains("extent")) spec.extent = float(r.number(t["extent"], ptr + "/extent", 1e-3, 1e9));
  // Procedural heights span [0, height_scale], so its bound is the height bound (kMaxAbsHeight);
  // for files the product with the stored values is checked when the file is read below.
  if (t.contains("height_scale"))
    spec.heightScale = float(r.number(t["height_scale"], ptr + "/height_scale", 0, procedural ? kMaxAbsHeight : 1e9));
  if (t.contains("width")) spec.rawWidth = r.integer(t["width"], ptr + "/width", 2, 65536);
  if (t.contains("height")) spec.rawHeight = r.integer(t["height"], ptr + "/height", 2, 65536);
  if (t.contains("origin")) {  // [x, z]: world position of the terrain's corner (scenario "far from the origin")
    if (!t["origin"].is_array() || t["origin"].size() != 2) r.fail(ptr + "/origin", "expected [x, z]");
    spec.originX = r.number(t["origin"][0], ptr + "/origin/0", -1e8, 1e8);
    spec.originZ = r.number(t["origin"][1], ptr + "/origin/1", -1e8, 1e8);
  }
  if (raw && (spec.rawWidth == 0 || spec.rawHeight == 0)) r.fail(ptr, "raw terrain needs 'width' and 'height'");
  if (t.contains("band")) spec.band = r.integer(t["band"], ptr + "/band", 1, 65535);
  if (t.contains("overview")) spec.overview = r.integer(t["overview"], ptr + "/overview", 1, 30);
  if (t.contains("window")) {  // [x, y, w, h] in the raster's pixels; checked against its size when read
    const json& w = t["window"];
    if (!w.is_array() || w.size() != 4) r.fail(ptr + "/window", "expected [x, y, width, height] in pixels");
    for (size_t i = 0; i < 4; ++i)
      spec.window.push_back(r.integer(w[i], ptr + "/window/" + std::to_string(i), i < 2 ? 0 : 2, 2147483647));
  }
  // Read the file now, so a bad heightmap stops the run before any case instead of failing each one.
  if (!procedural) {
    try {
      sharedHeightfield(spec);  // kept when large: the cases take it from there instead of reading it again
    } catch (const InputError& e) {
      r.fail(ptr + "/file", e.what());
    }
  }
  std::vector<TerrainSpec> out;
  if (t.contains("seed") && t["seed"].is_array()) {
    for (size_t i = 0; i < t["seed"].size(); ++i) {
      spec.seed = uint32_t(r.integer(t["seed"][i], ptr + "/seed/" + std::to_string(i), 0, 2147483647));
      out.push_back(spec);
    }
    if (out.empty()) r.fail(ptr + "/seed", "empty list");
  } else {
    if (t.contains("seed")) spec.seed = uint32_t(r.integer(t["seed"], ptr + "/seed", 0, 2147483647));
    out.push_back(spec);
  }
  return out;
}

void parseTerrainSection(const ConfigReader& r, const json& j, const std::string& baseDir, Config& c) {
  if (j.contains("terrain")) {
    auto t = parseTerrain(r, j["terrain"], "/terrain", baseDir);
    c.terrains.insert(c.terrains.end(), t.begin(), t.end());
  }
  if (j.contains("terrains")) {
    if (!j["terrains"].is_array()) r.fail("/terrains", "expected an array");
    for (size_t i = 0; i < j["terrains"].size(); ++i) {
      auto t = parseTerrain(r, j["terrains"][i], "/terrains/" + std::to_string(i), baseDir);
      c.terrains.insert(c.terrains.end(), t.begin(), t.end());
    }
  }
  if (c.terrains.empty()) c.terrains.push_back(TerrainSpec{});
}

}  // namespace lb
