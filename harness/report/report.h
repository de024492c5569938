#pragma once
// `lodbench report <run-dir>` (docs/design.md, Reports and regression checks): report.md, Vega-Lite chart specs with
// their data, and an HTML body, written into <run-dir>/report/; report/render.mjs (Node) then makes report.html
// (offline; the run's images linked, or embedded with --self-contained) and one SVG per chart. The harness never needs
// Node.
#include <string>
#include <vector>

namespace lb {

struct ReportOptions {
  std::string runDir;
  std::string outDir;          // default: <runDir>/report
  std::vector<int> frames;     // frames for the image strips; empty = every frame with images
  bool html = true;            // run render.mjs after writing
  bool selfContained = false;  // report.html embeds the images (default: links them, lazily loaded)
};

struct ReportOutput {
  std::string dir;
  int charts = 0, omittedCharts = 0;
  std::vector<std::string> notes;  // what the report could not show, and why
};

// Writes report.md, body.html, manifest.json, charts/<id>.vl.json and data/<name>.json.
// Throws InputError when runDir is not a run directory.
ReportOutput writeReport(const ReportOptions& options);

// Where render.mjs lives: $LODBENCH_REPORT_JS, else <source>/report.
std::string reportScriptDir();
// Why report.html cannot be rendered here ("" when node and report/node_modules are present).
std::string renderUnavailableReason();
// Runs `node render.mjs <dir> [--self-contained]`; returns its exit status.
int renderHtml(const std::string& reportDir, bool selfContained = false);

// The CLI subcommand: write, render when possible, print what was done. Returns the exit code.
int reportCommand(const ReportOptions& options);

}  // namespace lb
