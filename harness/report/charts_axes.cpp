// Axis domains a paper can print: padded so no point sits on the plot border, ends and ticks on
// round numbers, and a log axis where the data spans more than kLogDecades (GPU time with the
// reference scheme at 20x the others, triangle counts, error in px).
#include <algorithm>
#include <cmath>

#include "report/charts.h"

namespace lb {

using nlohmann::json;

namespace {

constexpr double kPad = 0.05;    // of the data's span (log axes: of its span in decades), each side
constexpr int kTargetTicks = 5;  // roughly; the step is the smallest round step giving at most ~7

std::vector<double> finite(const std::vector<double>& values) {
  std::vector<double> v;
  for (double x : values)
    if (std::isfinite(x)) v.push_back(x);
  return v;
}

// Smallest of 1, 2, 2.5, 5 x 10^k that is >= raw.
double roundStep(double raw) {
  double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * p >= raw * (1 - 1e-12)) return m * p;
  return 10 * p;
}

// Removes the binary noise of k * step (0.30000000000000004 -> 0.3).
double clean(double v, double step) {
  double r = std::round(v / step) * step;
  double digits = std::max(0.0, -std::floor(std::log10(step)) + 2);
  double scale = std::pow(10.0, digits);
  r = std::round(r * scale) / scale;
  return r == 0 ? 0.0 : r;  // no "-0"
}

std::string formatFor(const std::vector<double>& ticks) {
  double lo = INFINITY, hi = 0;
  for (double t : ticks) {
    lo = std::min(lo, std::fabs(t) > 0 ? std::fabs(t) : INFINITY);
    hi = std::max(hi, std::fabs(t));
  }
  return hi >= 10000 && lo >= 1 ? "~s" : "~f";  // 20k, 1M; never "1m" for 0.001; "~g" writes 80 as "8e+1"
}

AxisDomain linearDomain(const std::vector<double>& v) {
  AxisDomain d;
  double lo = *std::min_element(v.begin(), v.end()), hi = *std::max_element(v.begin(), v.end());
  double span = hi - lo;
  if (span <= 0) span = lo != 0 ? std::fabs(lo) * 0.4 : 1.0;  // one value: centred in a band around it
  double plo = lo - kPad * span, phi = hi + kPad * span;
  if (hi == lo) plo = lo - span / 2, phi = hi + span / 2;
  if (lo > 0 && plo < 0) plo = 0;  // positive data: the axis starts at zero at the lowest
  double step = roundStep((phi - plo) / kTargetTicks);
  d.lo = clean(std::floor(plo / step) * step, step);
  d.hi = clean(std::ceil(phi / step) * step, step);
  if (d.lo >= lo) d.lo = clean(d.lo - step, step);  // floor landed on the lowest value (plo == lo)
  if (d.hi <= hi) d.hi = clean(d.hi + step, step);
  for (double t = d.lo; t <= d.hi + step * 1e-9; t += step) d.ticks.push_back(clean(t, step));
  d.format = formatFor(d.ticks) == "~s" ? "," : "~f";  // linear: "20,000" (with "~s" Vega writes 0 as "0k")
  return d;
}

// Largest (down) or smallest (up) of 1, 2, 5 x 10^k on the given side of x.
double roundLog(double x, bool down) {
  double p = std::pow(10.0, std::floor(std::log10(x)));
  if (down) {
    for (double m : {5.0, 2.0, 1.0})
      if (m * p <= x * (1 + 1e-12)) return m * p;
    return p / 2;
  }
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= x * (1 - 1e-12)) return m * p;
  return 10 * p;
}

AxisDomain logDomain(const std::vector<double>& v) {
  AxisDomain d;
  d.type = "log";
  double lo = *std::min_element(v.begin(), v.end()), hi = *std::max_element(v.begin(), v.end());
  double decades = std::max(std::log10(hi / lo), 0.2);
  double plo = lo * std::pow(10.0, -kPad * decades), phi = hi * std::pow(10.0, kPad * decades);
  d.lo = roundLog(plo, true);
  d.hi = roundLog(phi, false);
  // Ticks at 1, 2, 5 x 10^k over up to three decades, at powers of ten beyond.
  bool fine = std::log10(d.hi / d.lo) <= 3.01;
  for (double p = std::pow(10.0, std::floor(std::log10(d.lo))); p <= d.hi * 1.000001; p *= 10)
    for (double m : {1.0, 2.0, 5.0}) {
      if (!fine && m != 1.0) continue;
      double t = m * p;
      double r = std::pow(10.0, std::floor(std::log10(t)) - 6);  // rounding to 7 digits
      t = std::round(t / r) * r;
      if (t >= d.lo * 0.999999 && t <= d.hi * 1.000001) d.ticks.push_back(t);
    }
  d.format = formatFor(d.ticks);
  return d;
}

}  // namespace

AxisDomain niceDomain(const std::vector<double>& values, AxisKind kind) {
  std::vector<double> v = finite(values);
  if (v.empty()) {
    AxisDomain d;
    d.ticks = {0, 0.5, 1};
    return d;
  }
  bool positive = std::all_of(v.begin(), v.end(), [](double x) { return x > 0; });
  bool log = positive && (kind == AxisKind::Log || (kind == AxisKind::Auto && scaleTypeFor(v) == "log"));
  return log ? logDomain(v) : linearDomain(v);
}

AxisDomain log2Domain(const std::vector<double>& values) {
  std::vector<double> v;
  for (double x : finite(values))
    if (x > 0) v.push_back(x);
  if (v.empty()) return niceDomain(values, AxisKind::Linear);
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  AxisDomain d;
  d.type = "log";
  d.lo = v.front() / std::pow(2.0, 0.25);
  d.hi = v.back() * std::pow(2.0, 0.25);
  d.ticks = v;
  d.format = "d";
  d.base = 2;
  return d;
}

std::string scaleTypeFor(const std::vector<double>& values) {
  double lo = INFINITY, hi = 0;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    if (v <= 0) return "linear";  // a log axis cannot show zero
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  return hi > 0 && std::log10(hi / lo) > kLogDecades ? "log" : "linear";
}

json scaleJson(const AxisDomain& d) {
  json s = {{"type", d.type}, {"domain", {d.lo, d.hi}}, {"nice", false}};
  if (d.type != "log") s["zero"] = false;  // Vega-Lite warns of zero on a log scale
  if (d.type == "log" && d.base != 10) s["base"] = d.base;
  return s;
}

json axisJson(const AxisDomain& d) {
  json a = {{"values", d.ticks}, {"format", d.format}, {"grid", true}};
  if (!d.labelExpr.empty()) a["labelExpr"] = d.labelExpr;
  return a;
}

json positionEncoding(const std::string& field, const std::string& title, const AxisDomain& d) {
  return {{"field", field},
          {"type", "quantitative"},
          {"title", d.type == "log" ? title + " (log)" : title},
          {"scale", scaleJson(d)},
          {"axis", axisJson(d)}};
}

json valueScale(const std::string& type) {
  // Round ends, and a few pixels so no point sits on the border.
  json s = {{"type", type}, {"nice", true}, {"padding", 6}};
  if (type != "log") s["zero"] = false;
  return s;
}

}  // namespace lb
