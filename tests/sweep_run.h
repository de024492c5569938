#pragma once
// Whole runs of a config from a test, as `lodbench run` makes them: into a fresh temporary folder,
// under the validation layer where ctest turns it on, every case required to finish without a
// failure or a validation message.
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lbtest {

// Runs cfg (paths in it relative to pathsDir, by default configs/) into a temporary folder named
// by tag and returns that folder; the caller reads and removes it.
std::filesystem::path runConfig(const nlohmann::json& cfg, const std::string& tag, const std::string& pathsDir = "");

// Every case record of a run folder.
std::vector<nlohmann::json> caseRecords(const std::filesystem::path& runDir);

// runConfig, then the case records, the folder removed.
std::vector<nlohmann::json> sweepCases(const nlohmann::json& cfg, const std::string& tag,
                                       const std::string& pathsDir = "");

// A case record's measured frames: frame -> the number at key (frames without it left out).
std::map<int, double> perFrame(const nlohmann::json& caseRecord, const std::string& key);

}  // namespace lbtest
