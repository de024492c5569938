#include "report/memory_table.h"

#include <cstdio>

namespace lb {

using nlohmann::json;

std::optional<double> memoryValue(const ReportCase& c, const char* field) {
  auto m = c.summary.find("memory");
  if (m == c.summary.end() || !m->is_object()) return std::nullopt;
  auto v = m->find(field);
  if (v == m->end() || !v->is_number()) return std::nullopt;
  return v->get<double>();
}

std::string mibText(const std::optional<double>& bytes) {
  if (!bytes) return formatValue(std::nullopt);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", *bytes / (1024.0 * 1024.0));
  return buf;
}

static std::optional<double> gpuBytes(const ReportCase& c, const char* resource) {
  auto m = c.summary.find("memory");
  if (m == c.summary.end() || !m->is_object() || !(*m)["gpu_bytes"].is_object()) return std::nullopt;
  const json& v = (*m)["gpu_bytes"][resource];
  return v.is_number() ? std::optional<double>(v.get<double>()) : std::nullopt;
}

Table memoryTable(const ReportRun& run) {
  Table t;
  t.header = {"case",          "heights MiB", "normal map MiB", "scheme tables MiB", "geometry MiB", "instances MiB",
              "LOD state MiB", "frame MiB",   "GPU total MiB",  "of it LOD MiB",     "capture MiB",  "host peak MiB"};
  t.numeric.assign(t.header.size(), true);
  t.numeric[0] = false;
  for (const ReportCase& c : run.cases) {
    if (c.status != "ok" || !c.summary.contains("memory")) continue;
    std::vector<Cell> row = {textCell(c.id)};
    for (const char* r : {"heights", "normal_map", "scheme_tables", "geometry", "instances", "lod_state", "frame"})
      row.push_back(textCell(mibText(gpuBytes(c, r))));
    for (const char* f : {"gpu_total_bytes", "gpu_lod_bytes", "gpu_capture_bytes", "host_peak_bytes"})
      row.push_back(textCell(mibText(memoryValue(c, f))));
    t.rows.push_back(std::move(row));
  }
  return t;
}

}  // namespace lb
