#include "compare/verdict.h"

#include <cstdio>
#include <map>
#include <sstream>
#include <tuple>

#include "results/write.h"
#include "version.h"

namespace lb {

using nlohmann::json;

namespace {

json side(const std::string& dir, const json& ctx) {
  json s = {{"dir", dir}};
  for (const char* key : {"git_commit", "device", "driver", "driver_info", "time", "host"})
    if (ctx.contains(key)) s[key] = ctx[key];
  return s;
}

std::string num(double v, const char* f = "%.4g") {
  char s[32];
  std::snprintf(s, sizeof s, f, v);
  return s;
}

std::string ctxText(const json& ctx, const char* key) {
  return ctx.contains(key) && ctx[key].is_string() ? ctx[key].get<std::string>() : "?";
}

std::string limitText(const CompareOptions& o) {
  return num(1 + o.threshold, "%.3g") + "x";
}

}  // namespace

std::string timingWords(const TimingCheck& t, const CompareOptions& o) {
  // A significant 1.56x slowdown under CI's 2x threshold used to read "unchanged": say
  // what the test found, and that it stays within the threshold.
  const bool significant = t.p < o.alpha;
  switch (t.verdict) {
    case TimingVerdict::Regression:
      return "REGRESSION: slower beyond the threshold (" + limitText(o) + ")";
    case TimingVerdict::Improvement:
      return "improvement: faster beyond the threshold (1/" + limitText(o) + ")";
    case TimingVerdict::Unchanged:
      if (!significant) return "no significant change";
      return std::string(t.ratio > 1 ? "slower" : "faster") + ", within the threshold (" + limitText(o) + ")";
    default:
      return "no timing verdict";
  }
}

std::string verdictLine(const CompareReport& r) {
  std::string line = r.exitCode() ? "REGRESSION in " + std::to_string(r.regressions()) + " of " +
                                        std::to_string(r.cases.size()) + " cases"
                                  : "no regression (" + std::to_string(r.cases.size()) + " cases)";
  // The figure people look for first: the largest GPU time ratio (candidate / baseline).
  const CaseComparison* worst = nullptr;
  for (auto& c : r.cases)
    if (c.timing.ratio > 0 && (!worst || c.timing.ratio > worst->timing.ratio)) worst = &c;
  if (!worst) return line + "; no GPU time ratio";
  const TimingCheck& t = worst->timing;
  line += "; GPU time ratio " + num(t.ratio, "%.3g") + "x";
  if (r.cases.size() > 1) line += " (largest, " + worst->id + ")";
  if (t.verdict != TimingVerdict::NotChecked) line += ", p = " + num(t.p, "%.2g");
  return line + ": " + timingWords(t, r.options);
}

json verdictJson(const CompareReport& r) {
  json cases = json::array();
  for (auto& c : r.cases) {
    json acc = json::array();
    for (auto& a : c.accuracy)
      acc.push_back({{"metric", a.metric},
                     {"baseline", a.baseline},
                     {"candidate", a.candidate},
                     {"higher_is_worse", a.higherIsWorse},
                     {"worse", a.worse}});
    const TimingCheck& t = c.timing;
    json timing = {{"verdict", timingVerdictName(t.verdict)},
                   {"verdict_text", timingWords(t, r.options)},
                   {"n_baseline", t.nBaseline},
                   {"n_candidate", t.nCandidate},
                   {"rounds_baseline", t.roundsBaseline},
                   {"rounds_candidate", t.roundsCandidate},
                   {"paired_rounds", t.pairedRounds}};
    if (t.verdict == TimingVerdict::NotChecked) timing["reason"] = t.reason;
    if (t.ratio > 0)
      timing.update({{"baseline_ms", t.baselineMs}, {"candidate_ms", t.candidateMs}, {"ratio", t.ratio}});
    if (t.verdict != TimingVerdict::NotChecked) timing.update({{"ci_lo", t.lo}, {"ci_hi", t.hi}, {"p", t.p}});
    json exact = {{"checked", c.exactChecked}, {"differs", c.exactDiffers}};
    if (c.exactDiffers)
      exact.update({{"first_frame", c.exact.frame},
                    {"field", c.exact.field},
                    {"baseline", c.exact.baseline},
                    {"candidate", c.exact.candidate},
                    {"frames_differing", c.exact.framesDiffering},
                    {"fields", c.exact.fields}});
    cases.push_back({{"case_id", c.id},
                     {"baseline_status", c.baselineStatus},
                     {"candidate_status", c.candidateStatus},
                     {"status_note", c.statusNote},
                     {"regression", !c.regressions.empty()},
                     {"regressions", c.regressions},
                     {"improved", c.improved},
                     {"exact", exact},
                     {"timing", timing},
                     {"accuracy", acc}});
    if (!c.split.empty()) {
      json split = json::object();
      for (auto& x : c.split) split[x.key] = {{"baseline", x.baseline}, {"candidate", x.candidate}};
      cases.back()["lod_draw_split"] = split;
    }
  }
  return {{"schema_version", kVerdictSchemaVersion},
          {"tool", "lodbench compare"},
          {"tool_version", kToolVersion},
          {"time", isoTimeUtc()},
          {"verdict", r.exitCode() ? "regression" : "clean"},
          {"summary", verdictLine(r)},
          {"exit_code", r.exitCode()},
          {"regressions", r.regressions()},
          {"improvements", r.improvements()},
          {"baseline", side(r.baselineDir, r.baselineContext)},
          {"candidate", side(r.candidateDir, r.candidateContext)},
          {"options",
           {{"threshold", r.options.threshold},
            {"alpha", r.options.alpha},
            {"error_tolerance", r.options.errorTolerance},
            {"require_exact", r.options.requireExact},
            {"min_rounds", r.options.minRounds}}},
          {"not_checked", r.notChecked},
          {"timing_method", kTimingMethod},
          {"exact", {{"checked", r.exactChecked}, {"skipped_reason", r.exactSkipReason}}},
          {"unmatched", {{"only_in_baseline", r.onlyInBaseline}, {"only_in_candidate", r.onlyInCandidate}}},
          {"notes", r.notes},
          {"cases", cases}};
}

std::string verdictMarkdown(const CompareReport& r) {
  std::ostringstream m;
  m << "# lodbench compare: " << verdictLine(r) << "\n\n";
  for (auto [label, dir, ctx] : {std::tuple{"Baseline", &r.baselineDir, &r.baselineContext},
                                 std::tuple{"Candidate", &r.candidateDir, &r.candidateContext}})
    m << "- " << label << ": `" << *dir << "` (commit " << ctxText(*ctx, "git_commit") << ", "
      << ctxText(*ctx, "device") << ", " << ctxText(*ctx, "driver_info") << ")\n";
  m << "- Regression: p < " << num(r.options.alpha) << " and GPU time ratio > " << num(1 + r.options.threshold)
    << "; accuracy tolerance " << num(r.options.errorTolerance * 100) << "%; " << r.improvements() << " improved\n";
  for (auto& n : r.notes) m << "- Note: " << n << "\n";
  if (!r.notChecked.empty()) {
    m << "\n## NOT CHECKED\n\n";
    for (auto& n : r.notChecked) m << "- **" << n << "**\n";
  }

  if (r.regressions()) {
    m << "\n## Regressions\n\n";
    for (auto& c : r.cases)
      for (auto& why : c.regressions) m << "- `" << c.id << "`: " << why << "\n";
  }

  m << "\n## Exact figures (counters, histograms, cracks)\n\n";
  if (!r.exactChecked) {
    m << "**NOT CHECKED**: " << r.exactSkipReason << ".\n";
  } else {
    int differing = 0;
    for (auto& c : r.cases) differing += c.exactDiffers;
    if (!differing)
      m << "Equal in every compared case.\n";
    else {
      m << "| case | first frame | field | baseline | candidate | frames differing | fields "
           "|\n|---|---|---|---|---|---|---|\n";
      for (auto& c : r.cases) {
        if (!c.exactDiffers) continue;
        std::string fields;
        for (auto& f : c.exact.fields) fields += (fields.empty() ? "" : ", ") + f;
        m << "| `" << c.id << "` | " << (c.exact.frame < 0 ? "-" : std::to_string(c.exact.frame)) << " | "
          << c.exact.field << " | " << c.exact.baseline << " | " << c.exact.candidate << " | "
          << c.exact.framesDiffering << " | " << fields << " |\n";
      }
    }
  }

  m << "\n## GPU time (medians of the rounds' median ms)\n\n";
  // A reason many rows share (too few rounds, typically every case) is said once: in NOT CHECKED
  // when it is there already, else above the table; the rows point to it.
  auto rowReason = [](const CaseComparison& c) { return c.statusNote.empty() ? c.timing.reason : c.statusNote; };
  std::map<std::string, int> reasons;
  for (auto& c : r.cases)
    if (c.timing.verdict == TimingVerdict::NotChecked) reasons[rowReason(c)]++;
  for (auto& [why, n] : reasons) {
    bool said = false;
    for (auto& note : r.notChecked) said = said || note.find(why) != std::string::npos;
    if (n > 1 && !said) m << "**NO VERDICT** for " << n << " of " << r.cases.size() << " cases: " << why << ".\n\n";
  }
  m << "| case | baseline | candidate | ratio [" << num((1 - r.options.alpha) * 100)
    << "% interval] | p | rounds | frames | verdict |\n"
    << "|---|---|---|---|---|---|---|---|\n";
  for (auto& c : r.cases) {
    const TimingCheck& t = c.timing;
    m << "| `" << c.id << "` | ";
    std::string rounds = t.pairedRounds ? std::to_string(t.roundsBaseline) + " pairs"
                                        : std::to_string(t.roundsBaseline) + " / " + std::to_string(t.roundsCandidate);
    if (t.verdict == TimingVerdict::NotChecked) {
      if (t.ratio > 0)
        m << num(t.baselineMs, "%.3f") << " | " << num(t.candidateMs, "%.3f") << " | " << num(t.ratio, "%.3f");
      else
        m << "- | - | -";
      m << " | - | " << rounds << " | " << t.nBaseline << " / " << t.nCandidate << " | "
        << (reasons[rowReason(c)] > 1 ? "no verdict (the reason above)" : "NO VERDICT: " + rowReason(c)) << " |\n";
      continue;
    }
    m << num(t.baselineMs, "%.3f") << " | " << num(t.candidateMs, "%.3f") << " | **" << num(t.ratio, "%.3f") << "x** ["
      << num(t.lo, "%.3f") << ", " << num(t.hi, "%.3f") << "] | " << num(t.p, "%.2g") << " | " << rounds << " | "
      << t.nBaseline << " / " << t.nCandidate << " | " << timingWords(t, r.options) << " |\n";
  }

  bool anySplit = false;
  for (auto& c : r.cases) anySplit |= !c.split.empty();
  if (anySplit) {
    m << "\n## LOD and draw (medians, ms; draw paths that time them apart, not judged)\n\n"
      << "| case | part | baseline | candidate |\n|---|---|---|---|\n";
    for (auto& c : r.cases)
      for (auto& x : c.split)
        m << "| `" << c.id << "` | " << x.key << " | " << num(x.baseline, "%.4f") << " | " << num(x.candidate, "%.4f")
          << " |\n";
  }

  bool anyAccuracy = false;
  for (auto& c : r.cases) anyAccuracy |= !c.accuracy.empty();
  if (anyAccuracy) {
    m << "\n## Accuracy (mean over measured frames)\n\n| case | metric | baseline | candidate | "
         "|\n|---|---|---|---|---|\n";
    for (auto& c : r.cases)
      for (auto& a : c.accuracy)
        m << "| `" << c.id << "` | " << a.metric << (a.higherIsWorse ? " (lower is better)" : " (higher is better)")
          << " | " << num(a.baseline) << " | " << num(a.candidate) << " | " << (a.worse ? "**worse**" : "ok") << " |\n";
  }

  if (!r.onlyInBaseline.empty() || !r.onlyInCandidate.empty()) {
    m << "\n## Unmatched cases (not compared)\n\n";
    for (auto& id : r.onlyInBaseline) m << "- only in the baseline: `" << id << "`\n";
    for (auto& id : r.onlyInCandidate) m << "- only in the candidate: `" << id << "`\n";
  }
  m << "\nMethod: " << kTimingMethod << ".\n";
  return m.str();
}

void writeVerdict(const CompareReport& r, const std::string& jsonPath, const std::string& mdPath) {
  if (!jsonPath.empty()) writeFileAtomic(jsonPath, verdictJson(r).dump(2) + "\n");
  if (!mdPath.empty()) writeFileAtomic(mdPath, verdictMarkdown(r));
}

}  // namespace lb
