#pragma once
// One parser per section of a config file, in the order parseConfig calls them (the order decides
// which error a config with several mistakes reports first). Each reads its keys of the config
// object j and fills its part of c; errors name file, line and field (config_reader.h).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "config/config.h"
#include "config/config_reader.h"

namespace lb {

// config_sections.cpp
void parseNameSection(const ConfigReader& r, const nlohmann::json& j, Config& c);        // name, device
void parseResolutionSection(const ConfigReader& r, const nlohmann::json& j, Config& c);  // resolution(s)
void parseGridSection(const ConfigReader& r, const nlohmann::json& j, Config& c);        // grid, grids
// fps, warmup_frames, max_frames, case_timeout_s, repetitions
void parseFrameSection(const ConfigReader& r, const nlohmann::json& j, Config& c);
// path, paths; returns the frames each path gives at the config's fps and max_frames.
std::vector<int> parsePathSection(const ConfigReader& r, const nlohmann::json& j, const std::string& baseDir,
                                  Config& c);
void parseImageSection(const ConfigReader& r, const nlohmann::json& j, const std::vector<int>& pathFrames, Config& c);

// config.cpp: terrain, terrains (each file is read now).
void parseTerrainSection(const ConfigReader& r, const nlohmann::json& j, const std::string& baseDir, Config& c);

// config.cpp: schemes and their parameter grids.
void parseSchemeSection(const ConfigReader& r, const nlohmann::json& j, Config& c);

// config_sections_timing.cpp
void parseTimingSection(const ConfigReader& r, const nlohmann::json& j, Config& c);       // timing modes
void parseCalibrationSection(const ConfigReader& r, const nlohmann::json& j, Config& c);  // clock control
void parseEnergySection(const ConfigReader& r, const nlohmann::json& j, Config& c);       // energy windows
void parseMeasureSection(const ConfigReader& r, const nlohmann::json& j, Config& c);
void parseMatchSection(const ConfigReader& r, const nlohmann::json& j, Config& c);

}  // namespace lb
