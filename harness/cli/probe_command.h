#pragma once
// `lodbench probe CONFIG`: the minimal loop (render/probe.h) at the config's grid, resolutions,
// timing modes and camera (first path, frame --frame), for each uniform level asked; with
// --compare, lodbench's renderer runs the same uniform level, pose and mode in the same process
// and each row gets ratio = minimal_ms / lodbench_ms. Writes {"device", "driver", "commit",
// "rows": [...]} (appending rows to an existing file with --append).
#include <string>
#include <vector>

namespace lb {

struct ProbeCommandOptions {
  std::string config;
  std::string device;       // overrides the config's
  std::vector<int> levels;  // default: the config's first scheme's value of the uniform-level main parameter, else 1
  std::vector<std::string> modes;  // default: the config's "timing"
  int frames = 100, warmup = 20, frame = 0;
  bool compare = false;
  bool vertexHeight = false;              // attribution variant of the minimal loop (ProbeOptions)
  std::string split = "auto";             // auto (lavapipe only) | on | off
  std::string drawPath = "tessellation";  // tessellation | instanced (ProbeOptions::instanced)
  std::string out;                        // "" = stdout only
  bool append = false;
};

int probeCommand(const ProbeCommandOptions& options);

}  // namespace lb
