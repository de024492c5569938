#include "report/report_side_by_side.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "report/report_answer.h"
#include "report/report_images.h"
#include "report/table.h"
#include "schemes/registry.h"

namespace lb {

namespace {

// What to compare a frame by: how it looks, how it was tessellated, where it is wrong.
const char* const kModes[] = {"shaded", "heatmap", "error"};

const std::map<std::string, std::string>* imagesAt(const ReportRun& run, const ReportCase& c, int frame) {
  auto imgs = run.images.find(c.id);
  if (c.status != "ok" || imgs == run.images.end()) return nullptr;
  auto f = imgs->second.find(frame);
  return f == imgs->second.end() || !f->second.count("shaded") ? nullptr : &f->second;
}

// The frame's own mean error when it was measured, else the case's mean over measured frames.
std::pair<std::optional<double>, bool> errorAt(const ReportCase& c, int frame) {
  for (auto& f : c.frames)
    if (frameValue(f, "frame") == double(frame))
      if (auto e = frameValue(f, "err_mean_px")) return {e, true};
  return {summaryStat(c.summary, "err_mean_px", "mean"), false};
}

// The scheme's default setting: the case at its main parameter's default, else the middle one.
const ReportCase* defaultCase(const std::vector<const ReportCase*>& cases) {
  const Scheme* s = findScheme(cases.front()->scheme);
  if (s && !s->info().mainParam.empty()) {
    const std::string& p = s->info().mainParam;
    for (const ParamSpec& spec : s->info().params)
      if (spec.name == p)
        for (auto* c : cases)
          if (!c->params.contains(p) || (c->params[p].is_number() && c->params[p].get<double>() == spec.defaultValue))
            return c;
  }
  return cases[cases.size() / 2];
}

std::string errorText(const SideBySideRow& r) {
  if (!r.error) return "no error measured (the run had no error pass)";
  return "mean error " + formatValue(*r.error) + " px" + (r.frameError ? "" : " (case mean; frame not measured)");
}

}  // namespace

SideBySide chooseSideBySide(const ReportRun& run) {
  SideBySide out;
  std::map<std::pair<std::string, int>, std::set<std::string>> schemesAt;  // (scenario, frame) -> schemes
  for (auto& c : run.cases) {
    auto imgs = run.images.find(c.id);
    if (imgs == run.images.end()) continue;
    for (auto& [frame, modes] : imgs->second)
      if (imagesAt(run, c, frame)) schemesAt[{c.scenario, frame}].insert(c.scheme);
  }
  size_t most = 1;
  for (auto& [key, schemes] : schemesAt)
    if (schemes.size() > 1 && (schemes.size() > most || (schemes.size() == most && key.second > out.frame)))
      most = schemes.size(), out.scenario = key.first, out.frame = key.second;
  if (out.frame < 0) return out;
  std::vector<double> errors;
  std::map<std::string, std::vector<const ReportCase*>> bySchemes;
  for (auto& c : run.cases)
    if (c.scenario == out.scenario && imagesAt(run, c, out.frame)) {
      bySchemes[c.scheme].push_back(&c);
      if (auto e = errorAt(c, out.frame).first) errors.push_back(*e);
    }
  out.target = errors.empty() ? 0 : medianOf(errors);
  for (const std::string& scheme : run.schemes) {
    auto it = bySchemes.find(scheme);
    if (it == bySchemes.end()) continue;
    const ReportCase* pick = nullptr;
    double bestDistance = 0;
    for (auto* c : it->second) {
      auto e = errorAt(*c, out.frame).first;
      if (!e || *e <= 0 || out.target <= 0) continue;
      double d = std::fabs(std::log(*e / out.target));
      if (d <= std::log(kMatchFactor) && (!pick || d < bestDistance)) pick = c, bestDistance = d;
    }
    SideBySideRow row{pick ? pick : defaultCase(it->second), std::nullopt, false, pick != nullptr};
    auto [e, own] = errorAt(*row.c, out.frame);
    row.error = e, row.frameError = own && e;
    out.rows.push_back(row);
  }
  return out;
}

std::pair<std::string, std::string> sideBySideSection(const ReportRun& run, const std::string& runHref) {
  SideBySide v = chooseSideBySide(run);
  if (v.frame < 0) return {"", ""};
  const std::string f = std::to_string(v.frame);
  std::string intro = (run.scenarios.size() > 1 ? "Path " + v.scenario + ", frame " : "Frame ") + f +
                      " (the frame with images of the most schemes), every scheme. ";
  intro += v.target > 0 ? "Each row shows the scheme's setting whose mean error on this frame is within " +
                              formatValue(kMatchFactor) + "x of " + formatValue(v.target) +
                              " px (the median over the cases imaged here), the closest one; a scheme without such "
                              "a setting shows its default setting instead, marked \"no match\"."
                        : "No case imaged here has an error measurement: every scheme shows its default setting.";
  intro += " Click an image to enlarge it.";
  std::string md = "\n## Side by side\n\n" + intro + "\n\n| scheme | setting | ";
  std::string html = "<h2 id=\"side-by-side\">Side by side</h2>\n<p>" + htmlEscape(intro) + "</p>\n";
  std::vector<std::string> modes;
  for (const char* m : kModes)
    if (std::any_of(v.rows.begin(), v.rows.end(), [&](auto& r) { return imagesAt(run, *r.c, v.frame)->count(m); }))
      modes.push_back(m);
  for (auto& m : modes) md += m + " | ";
  md += "\n|---|---|";
  for (size_t i = 0; i < modes.size(); ++i) md += "---|";
  md += "\n";
  // The flip viewer first: two schemes, one mode, one image that toggles between them.
  std::string options;
  for (auto& r : v.rows) options += "<option>" + htmlEscape(r.c->scheme) + "</option>";
  std::string modeOptions;
  for (auto& m : modes) modeOptions += "<option>" + htmlEscape(m) + "</option>";
  const SideBySideRow& a = v.rows.front();
  const SideBySideRow& b = v.rows.size() > 1 ? v.rows[1] : v.rows.front();
  std::string legends;
  for (auto& m : modes)
    if (!legendHtml(m).empty()) legends += "<div><b>" + htmlEscape(m) + "</b>" + legendHtml(m) + "</div>";
  html +=
      "<div class=\"flip-row\"><div class=\"flip\" id=\"flip\"><div class=\"flip-controls\">Flip between <select "
      "id=\"flip-a\">" +
      options + "</select> and <select id=\"flip-b\">" + options + "</select> in <select id=\"flip-mode\">" +
      modeOptions +
      "</select> <button type=\"button\" id=\"flip-button\">flip (F)</button> showing: <b id=\"flip-showing\">" +
      htmlEscape(a.c->scheme) + "</b></div>" +
      imageTag(run, runHref, imagesAt(run, *a.c, v.frame)->at("shaded"), "flip view") +
      "</div><div class=\"legends\">" + legends + "</div></div>\n";
  html += "<script>document.getElementById('flip-b').value = " + nlohmann::json(b.c->scheme).dump() + ";</script>\n";
  html += "<div class=\"side-grid\" style=\"grid-template-columns: 190px repeat(" + std::to_string(modes.size()) +
          ", 320px)\"><div></div>";
  for (auto& m : modes) html += "<div class=\"side-head\">" + htmlEscape(m) + "</div>";
  for (auto& r : v.rows) {
    const auto* imgs = imagesAt(run, *r.c, v.frame);
    std::string label = r.c->paramsLabel + ", " + errorText(r) + (r.matched ? "" : "; no match: default setting");
    md += "| " + r.c->scheme + " | " + label + " | ";
    html += "<div class=\"side-label\"><b>" + htmlEscape(r.c->scheme) + "</b><br>" + htmlEscape(label) + "</div>";
    for (auto& m : modes) {
      auto it = imgs->find(m);
      if (it == imgs->end()) {
        md += "(no " + m + " image) | ";
        html += "<div class=\"no-image\">no " + htmlEscape(m) + " image of this case</div>";
        continue;
      }
      md += "![" + m + "](" + runHref + "/" + it->second + ") | ";
      std::string tag = imageTag(run, runHref, it->second, r.c->scheme + " " + m);
      tag.insert(tag.size() - 1,
                 " data-scheme=\"" + htmlEscape(r.c->scheme) + "\" data-mode=\"" + htmlEscape(m) + "\"");
      html += "<div class=\"shot side-shot\">" + tag + "</div>";
    }
    md += "\n";
  }
  html += "</div>\n";
  return {md + "\n", html};
}

}  // namespace lb
