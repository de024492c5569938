#pragma once
// A run/sweep config (JSON). Its cases are the cartesian product of schemes x parameter values x
// camera paths x terrains x resolutions.
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "config/match_spec.h"
#include "config/measure_spec.h"
#include "config/timing_spec.h"
#include "render/scheme.h"
#include "schemes/registry.h"
#include "terrain/heightfield.h"

namespace lb {

struct SchemeEntry {
  std::string name;
  std::string field;                  // JSON pointer of the entry ("/schemes/2"); a group's schemes share its entry's
  std::vector<ParamValues> variants;  // expanded parameter grid (at least one, possibly empty map)
  // "tune": the settings a tuned matched search tries ("grid" or a parameter: values); given =
  // the entry listed it (else a tuned match uses the registry's space, schemes/registry.h).
  TuneSpace tune;
  bool tuneGiven = false;
};

struct ImageRequest {
  std::vector<int> frames;         // path frame indices (negative counts from the end)
  std::vector<std::string> modes;  // shaded | heatmap | wireframe | error | cracks
  // Size of the images: a case's frames are drawn at this size with the case's own
  // tessellation (replay/case_images.h); a case of another aspect ratio gets the smallest size of
  // its aspect ratio that covers it.
  int width = 640, height = 360;
  bool worst = true;  // also image each case's worst measured frames (summary worst_frames)
};

struct Config {
  std::string file;  // where it was read from (for messages)
  // Line of each JSON pointer of the file (config/json_lines.h), so checks after parsing (duplicate
  // entries in expandCases, the device) name file, line and field too; empty for a Config built in code.
  std::map<std::string, int> lines;
  std::string name = "run";
  std::string device;  // "" = default (lavapipe where present)
  // Where `device` was named when the config named it: "c.json:3: field '/device'"; "" when it is
  // the default or the command line's (run --device clears it), so a device that matches nothing
  // is reported against what named it (ContextOptions::deviceWhere).
  std::string deviceWhere;
  std::vector<std::pair<int, int>> resolutions{{320, 180}};
  int grid = 32;
  std::vector<int> grids{32};  // "grid" or "grids": one case per grid (scale studies)
  double fps = 30;
  int warmupFrames = 5;
  int maxFrames = 0;  // 0 = every frame of the path
  int repetitions = 1;
  // true: the repetitions run as rounds across the sweep (every case once, then every case again),
  // so clock and thermal drift fall on every scheme alike (sweep/runner.h).
  bool interleave = false;
  double caseTimeoutS = 0;  // a case running longer fails with "timeout" (0 = no limit)
  std::vector<TerrainSpec> terrains;
  std::vector<std::string> paths;  // resolved file paths
  // JSON pointer of each entry of `terrains` and `paths` ("/terrains/1", "/terrain/seed/2", "/paths/0")
  // for messages about them; empty for a Config built in code.
  std::vector<std::string> terrainFields, pathFields;
  // "schemes": one entry per scheme, a group ("all", schemes/registry.h schemeGroup) expanded to
  // its schemes that no other entry names.
  std::vector<SchemeEntry> schemes;
  std::vector<std::string> plugins;  // "plugins": scheme libraries loaded while parsing (schemes/plugins.h)
  ImageRequest images;
  MeasureSpec measure;      // measurement passes (off unless "measure" is given)
  MatchSpec match;          // matched comparisons (off unless "match" is given)
  TimingSpec timing;        // timing modes and calibration ("timing", "calibration")
  nlohmann::json raw;       // the config as written, recorded in results
  double testSlowdown = 0;  // `run --test-slowdown` (tests only, never from JSON): see RenderSettings
};

struct Case {
  std::string id;
  std::string scheme;
  ParamValues params;        // every parameter of the scheme, defaults resolved
  ParamValues listedParams;  // those the config lists (the case id and labels name these)
  TerrainSpec terrain;
  std::string terrainLabel;
  std::string path;
  int width = 0, height = 0;
  int grid = 32;
  TuneSpace tune;  // a tuned matched search's space (empty: the main parameter alone)
  // What defines the case (config/case_identity.h) and its SHA-256: resume reuses a finished
  // case only when the digest is unchanged.
  nlohmann::json inputs;
  std::string digest;
  std::string terrainDigest;  // of the terrain alone: keys the reference images of this terrain
};

// Throws lb::InputError "file:line: field: problem".
Config loadConfig(const std::string& file);
Config parseConfig(const std::string& text, const std::string& file, const std::string& baseDir);
// Case ids are readable (scheme-params_terrain_path_WxH) and unique: where the readable parts of
// two different cases coincide, each gets a short digest suffix; terrains whose labels coincide
// get one in their label. Duplicate entries (the same terrain, path contents, resolution or scheme
// and parameters twice) are an InputError naming both.
std::vector<Case> expandCases(const Config& config);
std::string terrainLabel(const TerrainSpec& t);
// "file:line: field '/ptr'" (config_reader.h's form) for a field of a parsed config; the line is
// left out where it is not known (a Config built in code).
std::string configField(const Config& config, const std::string& ptr);

}  // namespace lb
