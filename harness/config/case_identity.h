#pragma once
// What defines a case, recorded in its case file as "inputs" with their SHA-256 "digest":
// terrain spec and heightmap file contents, camera path file contents, resolution, scheme and
// every parameter with its resolved value, every setting that shapes the records, the tool
// version, and for a plugin's scheme the library's SHA-256 and plugin API version (a rebuilt
// plugin's cases run again on resume). File names are not part of it (contents are), so a run
// resumes from another working directory. Resume reuses a finished case only when its digest is unchanged, and a config
// that grows resumes its folder, so the digest is all that stands between a kept case and one whose numbers meant
// something else: a change of what a parameter, setting or metric means, or of what these records hold, bumps the tool
// version (version.h). expandCases uses the digest to keep case ids unique.
#include <map>
#include <nlohmann/json.hpp>
#include <string>

namespace lb {

struct Config;
struct TerrainSpec;

// File path -> SHA-256 of its contents, so a sweep reads each file once.
using FileDigests = std::map<std::string, std::string>;

nlohmann::json terrainInputs(const TerrainSpec& t, FileDigests& files);
nlohmann::json pathInputs(const std::string& path, FileDigests& files);
// Settings of the config that shape every case's results (frames, timing, measurements).
nlohmann::json measurementInputs(const Config& config);
nlohmann::json caseInputs(const nlohmann::json& terrain, const nlohmann::json& path, int width, int height,
                          const std::string& scheme, const nlohmann::json& params, const nlohmann::json& measurement);
std::string inputsDigest(const nlohmann::json& inputs);
// What differs between a recorded and a current inputs record, e.g. "path contents (sha256
// 1a2b3c4d -> 5e6f7a8b)", "terrain.extent 1000 -> 2000"; "" when equal.
std::string describeInputChange(const nlohmann::json& recorded, const nlohmann::json& now);

}  // namespace lb
