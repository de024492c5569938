#include "results/run_read.h"

namespace lb {

using nlohmann::json;

static std::string str(const json& j, const char* key) {
  auto it = j.find(key);
  return it != j.end() && it->is_string() ? it->get<std::string>() : std::string();
}

void readCaseRecord(CaseRecord& c, const json& j) {
  if (j.contains("scheme")) c.scheme = str(j, "scheme");
  if (j.contains("status")) c.status = str(j, "status");
  if (j.contains("reason")) c.reason = str(j, "reason");
  if (j.contains("path")) c.path = str(j, "path");
  if (j.contains("params") && j["params"].is_object()) c.params = c.listedParams = j["params"];
  if (j.contains("params_listed") && j["params_listed"].is_object()) c.listedParams = j["params_listed"];
  if (j.contains("summary") && j["summary"].is_object()) c.summary = j["summary"];
  if (j.contains("frames") && j["frames"].is_array()) c.frames = j["frames"];
  if (auto t = j.find("terrain"); t != j.end())
    c.terrain = t->is_object() ? str(*t, "label") : t->is_string() ? t->get<std::string>() : "";
  if (auto r = j.find("resolution");
      r != j.end() && r->is_array() && r->size() == 2 && (*r)[0].is_number_integer() && (*r)[1].is_number_integer()) {
    c.width = (*r)[0].get<int>();
    c.height = (*r)[1].get<int>();
  }
  if (auto g = j.find("grid"); g != j.end() && g->is_number_integer()) {
    c.grid = g->get<int>();
  } else if (auto in = j.find("inputs"); in != j.end() && in->is_object() && in->contains("measurement")) {
    const json& m = (*in)["measurement"];
    if (m.is_object() && m.contains("grid") && m["grid"].is_number_integer()) c.grid = m["grid"].get<int>();
  }
  if (auto t = j.find("target_area_px"); t != j.end() && t->is_number()) c.targetAreaPx = t->get<double>();
  if (auto m = j.find("matched"); m != j.end() && m->is_object()) c.matched = *m;
}

}  // namespace lb
