// fccp handles the CSV structure (header matching, comments, column counts); numbers are
// converted here with std::from_chars, because fccp's float parser reads an empty field as 0
// and accumulates decimal digits with rounding error.
#include "camera/camera_path.h"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

// fccp's bounded strncpy of file names trips -Wstringop-truncation once inlined; it is intended.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wstringop-truncation"
#endif
#include <libfccp/csv.h>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

#include "error.h"
#include "terrain/heightfield.h"

namespace lb {
namespace {

// Every column a header may name; the first 8 are the original format's.
enum Column {
  kTime,
  kEyeX,
  kEyeY,
  kEyeZ,
  kTargetX,
  kTargetY,
  kTargetZ,
  kFov,
  kEyeAgl,
  kEyeAglSp,
  kTargetAgl,
  kTargetAglSp,
  kEyeDxSp,
  kEyeDzSp,
  kTargetDxSp,
  kTargetDzSp,
  kColumns
};
const char* const kColumnNames[kColumns] = {
    "time",    "eye_x",      "eye_y",      "eye_z",         "target_x",  "target_y",  "target_z",     "fov",
    "eye_agl", "eye_agl_sp", "target_agl", "target_agl_sp", "eye_dx_sp", "eye_dz_sp", "target_dx_sp", "target_dz_sp"};
const char* const kHeader = "time,eye_x,eye_y,eye_z,target_x,target_y,target_z,fov";
constexpr double kMinFovDeg = 1, kMaxFovDeg = 170;
// Relative coordinates beyond these are almost certainly world units or a typo, not a choice.
constexpr double kMinXZ = -1, kMaxXZ = 2, kMinY = -1, kMaxY = 10;
// Spacing counts: a million spacings is 30x the side of the largest terrain a device takes.
constexpr double kMaxSpacings = 1e6;
constexpr double kGroundClearance = 0.002;  // fraction of the extent; keeps the near plane above ground
// Keyframes closer than this in time are refused: the spline's tangents divide by the step, so keys
// 1e-300 s apart give velocities of 1e300 extents/s (inf and NaN poses). At 1 us the steepest
// chord (3 extents) is 3e6 extents/s, finite, and no path sampled at up to 1e6 fps needs closer keys.
constexpr double kMinKeyStepS = 1e-6;  // the message below says "1e-6 s"

// Each column's accepted range and what its unit is, for the range message (fov and time apart).
struct ColumnRange {
  double lo, hi;
  const char* unit;
};
ColumnRange rangeOf(int col) {
  switch (col) {
    case kEyeY:
    case kTargetY:
      return {kMinY, kMaxY, "y is in units of the extent above the lowest terrain point"};
    case kEyeAgl:
      return {0, kMaxY, "eye_agl is in units of the extent above the ground under the eye"};
    case kTargetAgl:
      return {-kMaxY, kMaxY, "target_agl is in units of the extent above the ground under the eye"};
    case kEyeAglSp:
      return {0, kMaxSpacings, "eye_agl_sp is in sample spacings above the ground under the eye"};
    case kTargetAglSp:
      return {-kMaxSpacings, kMaxSpacings, "target_agl_sp is in sample spacings above the ground under the eye"};
    case kEyeDxSp:
    case kEyeDzSp:
    case kTargetDxSp:
    case kTargetDzSp:
      return {-kMaxSpacings, kMaxSpacings, "*_dx_sp and *_dz_sp are sample spacings added to x and z"};
    default:
      return {kMinXZ, kMaxXZ, "x and z are fractions of the terrain extent"};
  }
}

// Blank lines are tolerated as well as '#' comments: a stray empty line is not worth an error.
using Reader = io::CSVReader<kColumns, io::trim_chars<' ', '\t'>, io::no_quote_escape<','>, io::throw_on_overflow,
                             io::single_and_empty_line_comment<'#'>>;

std::string num(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

[[noreturn]] void fail(const std::string& file, unsigned line, const std::string& what) {
  throw InputError(file + ":" + std::to_string(line) + ": " + what);
}

[[noreturn]] void failColumn(const std::string& file, unsigned line, int col, const std::string& what) {
  fail(file, line, std::string("column '") + kColumnNames[col] + "': " + what);
}

// Line n (1-based) of text as fccp sees it: '\n' separated, trailing '\r' and a leading BOM dropped.
std::string lineOf(const std::string& text, unsigned n) {
  size_t begin = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  for (unsigned i = 1; i < n && begin != std::string::npos; ++i) {
    begin = text.find('\n', begin);
    if (begin != std::string::npos) ++begin;
  }
  if (begin == std::string::npos) return {};
  std::string line = text.substr(begin, text.find('\n', begin) - begin);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return line;
}

std::vector<std::string> splitFields(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  for (std::string f; std::getline(in, f, ',');) {
    f.erase(0, f.find_first_not_of(" \t"));
    f.erase(f.find_last_not_of(" \t") + 1);
    out.push_back(f);
  }
  if (!line.empty() && line.back() == ',') out.emplace_back();  // getline drops a trailing empty field
  return out;
}

// fccp's own messages lack the line for header errors and never say which value is missing,
// so rebuild them from the error type and the source text.
std::string describe(const io::error::base& e, const std::string& text, unsigned line, unsigned headerLine) {
  using namespace io::error;
  const std::string expected = std::string(" (expected '") + kHeader + "')";
  if (auto* c = dynamic_cast<const extra_column_in_header*>(&e))
    return "header: unexpected column '" + printable(c->column_name) + "'" + expected;
  if (auto* c = dynamic_cast<const missing_column_in_header*>(&e))
    return "header: missing column '" + printable(c->column_name) + "'" + expected;
  if (auto* c = dynamic_cast<const duplicated_column_in_header*>(&e))
    return "header: column '" + printable(c->column_name) + "' appears twice";
  if (dynamic_cast<const header_missing*>(&e))
    return (line == 0 ? "file is empty" : "no header line before the end of the file") + expected;
  if (dynamic_cast<const too_few_columns*>(&e) || dynamic_cast<const too_many_columns*>(&e)) {
    const size_t got = splitFields(lineOf(text, line)).size();
    const std::vector<std::string> header = splitFields(lineOf(text, headerLine));
    if (got < header.size())
      return "column '" + printable(header[got]) + "': missing (" + std::to_string(got) + " of " +
             std::to_string(header.size()) + " values)";
    return std::to_string(got) + " values, but the header has " + std::to_string(header.size()) + " columns";
  }
  if (dynamic_cast<const line_length_limit_exceeded*>(&e)) return "line too long";
  return printable(e.what(), 200);
}

double parseNumber(const char* raw, const std::string& file, unsigned line, int col) {
  const char* begin = raw;
  const char* end = raw + std::strlen(raw);
  if (begin == end) failColumn(file, line, col, "value is empty");
  // from_chars rejects the leading '+' that strtod and spreadsheets accept.
  if (*begin == '+' && end - begin > 1 && begin[1] != '-' && begin[1] != '+') ++begin;
  double v = 0;
  auto [ptr, ec] = std::from_chars(begin, end, v);
  if (ec == std::errc::result_out_of_range) failColumn(file, line, col, "'" + printable(raw) + "' is out of range");
  if (ec != std::errc() || ptr != end) failColumn(file, line, col, "'" + printable(raw) + "' is not a number");
  if (!std::isfinite(v)) failColumn(file, line, col, "'" + printable(raw) + "' is not finite");
  return v;
}

void checkRange(double v, int col, const std::string& file, unsigned line) {
  const ColumnRange r = rangeOf(col);
  if (v < r.lo || v > r.hi)
    failColumn(file, line, col, num(v) + " is outside [" + num(r.lo) + ", " + num(r.hi) + "] (" + r.unit + ")");
}

// Which columns the header named, checked as a set: fccp reads them in any order and leaves the
// absent ones null.
struct Layout {
  bool has[kColumns] = {};
  PathHeight eyeHeight = PathHeight::AboveLowest, targetHeight = PathHeight::AboveLowest;
  bool steps = false;
};

// One of y, agl, agl_sp for the eye (or the target): exactly one must be present.
PathHeight heightColumn(const Layout& l, int y, int agl, int aglSp, const std::string& file, unsigned line) {
  std::vector<int> given;
  for (int c : {y, agl, aglSp})
    if (l.has[c]) given.push_back(c);
  if (given.empty())
    fail(file, line,
         std::string("header: missing column '") + kColumnNames[y] + "' (or '" + kColumnNames[agl] + "' or '" +
             kColumnNames[aglSp] + "' for a height above the ground) (expected '" + kHeader + "')");
  if (given.size() > 1)
    fail(file, line,
         std::string("header: columns '") + kColumnNames[given[0]] + "' and '" + kColumnNames[given[1]] +
             "' both give the " + (y == kEyeY ? "eye" : "target") + "'s height; keep one");
  return given[0] == y     ? PathHeight::AboveLowest
         : given[0] == agl ? PathHeight::AboveGround
                           : PathHeight::SpacingsAboveGround;
}

Layout checkLayout(const Reader& reader, const std::string& file, unsigned line) {
  Layout l;
  for (int c = 0; c < kColumns; ++c) l.has[c] = reader.has_column(kColumnNames[c]);
  // In the original header's order, so a file of that format hears about its first missing column.
  for (int c : std::initializer_list<int>{kTime, kEyeX, -1, kEyeZ, kTargetX, -2, kTargetZ, kFov}) {
    if (c == -1) l.eyeHeight = heightColumn(l, kEyeY, kEyeAgl, kEyeAglSp, file, line);
    if (c == -2) l.targetHeight = heightColumn(l, kTargetY, kTargetAgl, kTargetAglSp, file, line);
    if (c >= 0 && !l.has[c])
      fail(file, line, std::string("header: missing column '") + kColumnNames[c] + "' (expected '" + kHeader + "')");
  }
  l.steps = l.has[kEyeDxSp] || l.has[kEyeDzSp] || l.has[kTargetDxSp] || l.has[kTargetDzSp];
  return l;
}

Keyframe parseRow(const char* const (&field)[kColumns], const Layout& l, const std::string& file, unsigned line) {
  double v[kColumns] = {};
  for (int c = 0; c < kColumns; ++c)
    if (l.has[c]) v[c] = parseNumber(field[c], file, line, c);
  for (int c = 1; c < kColumns; ++c)
    if (l.has[c] && c != kFov) checkRange(v[c], c, file, line);
  if (!(v[kFov] > kMinFovDeg && v[kFov] < kMaxFovDeg))
    failColumn(file, line, kFov,
               num(v[kFov]) + " degrees is outside (" + num(kMinFovDeg) + ", " + num(kMaxFovDeg) + ")");
  auto height = [&](PathHeight h, int y, int agl, int aglSp) {
    return h == PathHeight::AboveLowest ? v[y] : h == PathHeight::AboveGround ? v[agl] : v[aglSp];
  };
  Keyframe k;
  k.time = v[kTime];
  k.eye = {v[kEyeX], height(l.eyeHeight, kEyeY, kEyeAgl, kEyeAglSp), v[kEyeZ]};
  k.target = {v[kTargetX], height(l.targetHeight, kTargetY, kTargetAgl, kTargetAglSp), v[kTargetZ]};
  k.eyeStepSp = {v[kEyeDxSp], 0.0, v[kEyeDzSp]};
  k.targetStepSp = {v[kTargetDxSp], 0.0, v[kTargetDzSp]};
  k.fovDeg = v[kFov];
  // Only where both are in one unit can a keyframe alone show the target on the eye.
  if (l.eyeHeight == l.targetHeight && glm::length(k.target - k.eye) < 1e-9 &&
      glm::length(k.targetStepSp - k.eyeStepSp) < 1e-9)
    fail(file, line, "columns 'target_x/y/z': target equals the eye position");
  return k;
}

void checkFps(double fps) {
  if (!(fps > 0) || !std::isfinite(fps))
    throw InputError("frame rate (fps) must be a positive finite number, got " + num(fps));
}

// Tangent in relative units per second. Interior keys use the Barry-Goldman (non-uniform
// Catmull-Rom) derivative, a duration-weighted mean of the neighbouring chord slopes, so velocity
// stays continuous across unevenly spaced keys. End keys act as if the endpoint were duplicated,
// which halves the adjacent slope.
glm::dvec3 tangent(const std::vector<Keyframe>& keys, size_t i, glm::dvec3 Keyframe::*p) {
  auto slope = [&](size_t a) { return (keys[a + 1].*p - keys[a].*p) / (keys[a + 1].time - keys[a].time); };
  if (i == 0) return 0.5 * slope(0);
  if (i + 1 == keys.size()) return 0.5 * slope(i - 1);
  const double hPrev = keys[i].time - keys[i - 1].time, hNext = keys[i + 1].time - keys[i].time;
  return (hNext * slope(i - 1) + hPrev * slope(i)) / (hPrev + hNext);
}

glm::dvec3 hermite(const std::vector<Keyframe>& keys, size_t i, double s, glm::dvec3 Keyframe::*p) {
  const double h = keys[i + 1].time - keys[i].time, s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * (keys[i].*p) + (s3 - 2 * s2 + s) * h * tangent(keys, i, p) +
         (-2 * s3 + 3 * s2) * (keys[i + 1].*p) + (s3 - s2) * h * tangent(keys, i + 1, p);
}

}  // namespace

CameraPath parseCameraPath(const std::string& text, const std::string& nameForErrors) {
  CameraPath path;
  path.file = nameForErrors;
  Reader reader(nameForErrors, text.data(), text.data() + text.size());
  unsigned headerLine = 0;
  try {
    // Missing columns are checked as a set by checkLayout (one of the alternatives for a height).
    reader.read_header(io::ignore_missing_column, kColumnNames[0], kColumnNames[1], kColumnNames[2], kColumnNames[3],
                       kColumnNames[4], kColumnNames[5], kColumnNames[6], kColumnNames[7], kColumnNames[8],
                       kColumnNames[9], kColumnNames[10], kColumnNames[11], kColumnNames[12], kColumnNames[13],
                       kColumnNames[14], kColumnNames[15]);
    headerLine = reader.get_file_line();
    const Layout layout = checkLayout(reader, nameForErrors, headerLine);
    path.eyeHeight = layout.eyeHeight;
    path.targetHeight = layout.targetHeight;
    path.spacingSteps = layout.steps;
    const char* f[kColumns] = {};
    unsigned prevLine = 0;
    while (reader.read_row(f[0], f[1], f[2], f[3], f[4], f[5], f[6], f[7], f[8], f[9], f[10], f[11], f[12], f[13],
                           f[14], f[15])) {
      const unsigned line = reader.get_file_line();
      Keyframe k = parseRow(f, layout, nameForErrors, line);
      if (!path.keys.empty() && !(k.time > path.keys.back().time))
        failColumn(nameForErrors, line, 0,
                   num(k.time) + " is not after the previous keyframe's " + num(path.keys.back().time) + " (line " +
                       std::to_string(prevLine) + "); times must strictly increase");
      if (!path.keys.empty() && !(k.time - path.keys.back().time >= kMinKeyStepS))
        failColumn(nameForErrors, line, 0,
                   num(k.time) + " is only " + num(k.time - path.keys.back().time) +
                       " s after the previous keyframe's " + num(path.keys.back().time) + " (line " +
                       std::to_string(prevLine) + "); keyframes must be at least 1e-6 s apart");
      path.keys.push_back(k);
      prevLine = line;
    }
  } catch (const io::error::base& e) {
    const unsigned line = reader.get_file_line();
    fail(nameForErrors, std::max(line, 1u), describe(e, text, line, headerLine));
  }
  if (path.keys.size() < 2)
    fail(nameForErrors, std::max(reader.get_file_line(), 1u),
         "keyframes: found " + std::to_string(path.keys.size()) + ", a camera path needs at least 2");
  return path;
}

CameraPath loadCameraPath(const std::string& file) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) throw InputError("cannot open camera path " + file + ": is a directory");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("cannot open camera path " + file);
  std::ostringstream text;
  text << in.rdbuf();
  return parseCameraPath(text.str(), file);
}

Keyframe interpolate(const CameraPath& path, double t) {
  const std::vector<Keyframe>& keys = path.keys;
  if (keys.empty()) throw InputError(path.file + ": camera path has no keyframes");
  if (!(t > keys.front().time)) return keys.front();  // also catches NaN
  if (!(t < keys.back().time)) return keys.back();
  // First key strictly after t; the segment starts one before it, so t at a key time gives s == 0.
  auto next = std::upper_bound(keys.begin(), keys.end(), t, [](double v, const Keyframe& k) { return v < k.time; });
  const size_t i = static_cast<size_t>(next - keys.begin()) - 1;
  const double s = (t - keys[i].time) / (keys[i + 1].time - keys[i].time);
  Keyframe k;
  k.time = t;
  k.eye = hermite(keys, i, s, &Keyframe::eye);
  k.target = hermite(keys, i, s, &Keyframe::target);
  if (path.spacingSteps) {
    k.eyeStepSp = hermite(keys, i, s, &Keyframe::eyeStepSp);
    k.targetStepSp = hermite(keys, i, s, &Keyframe::targetStepSp);
  }
  k.fovDeg = keys[i].fovDeg + (keys[i + 1].fovDeg - keys[i].fovDeg) * s;
  return k;
}

int frameCount(const CameraPath& path, double fps) {
  checkFps(fps);
  // The epsilon keeps a 10 s path at 60 fps from losing its last frame to 599.99999.
  const double frames = std::floor(path.duration() * fps + 1e-9);
  if (frames >= static_cast<double>(INT_MAX - 1))
    throw InputError(path.file + ": " + num(fps) + " fps over " + num(path.duration()) + " s is too many frames");
  return static_cast<int>(frames) + 1;
}

CameraPose terrainLocalPose(const CameraPose& pose, const Heightfield& terrain) {
  const glm::dvec3 o(terrain.originX, 0.0, terrain.originZ);
  CameraPose local = pose;
  local.eye = glm::vec3(glm::dvec3(pose.eye) - o);
  local.target = glm::vec3(glm::dvec3(pose.target) - o);
  return local;
}

double sampleSpacing(const Heightfield& terrain) {
  const int samples = std::max(terrain.width, terrain.height);
  return samples > 1 ? double(terrain.extent) / double(samples - 1) : double(terrain.extent);
}

namespace {

// The original format: every coordinate relative to the extent and the lowest point, the eye kept
// 0.002 extent above the ground. Kept as it was, so shipped paths sample bit-identical poses.
CameraPose extentPose(const Keyframe& k, const Heightfield& terrain) {
  const double extent = terrain.extent;
  auto toWorld = [&](const glm::dvec3& r) {
    return glm::vec3(glm::dvec3(r.x * extent, r.y * extent + terrain.minHeight, r.z * extent));
  };
  CameraPose pose;
  pose.eye = toWorld(k.eye);
  pose.target = toWorld(k.target);
  pose.fovDeg = static_cast<float>(k.fovDeg);
  const float ground = terrain.sample(pose.eye.x, pose.eye.z) + static_cast<float>(kGroundClearance * extent);
  pose.eye.y = std::max(pose.eye.y, ground);
  return pose;
}

// Scale-free columns: x and z from the extent plus spacings, heights from the lowest point or the
// ground under the eye (looked up here, per sampled frame, after the relative values were
// interpolated). Computed in double, rounded to float once per coordinate.
CameraPose groundPose(const CameraPath& path, const Keyframe& k, const Heightfield& terrain) {
  const double extent = terrain.extent, spacing = sampleSpacing(terrain);
  auto horizontal = [&](double fraction, double steps) { return float(fraction * extent + steps * spacing); };
  CameraPose pose;
  pose.fovDeg = static_cast<float>(k.fovDeg);
  pose.eye.x = horizontal(k.eye.x, k.eyeStepSp.x);
  pose.eye.z = horizontal(k.eye.z, k.eyeStepSp.z);
  pose.target.x = horizontal(k.target.x, k.targetStepSp.x);
  pose.target.z = horizontal(k.target.z, k.targetStepSp.z);
  const double ground = terrain.sample(pose.eye.x, pose.eye.z);  // under the eye: both heights' reference
  auto height = [&](PathHeight h, double v) {
    return h == PathHeight::AboveLowest   ? v * extent + terrain.minHeight
           : h == PathHeight::AboveGround ? ground + v * extent
                                          : ground + v * spacing;
  };
  double eyeY = height(path.eyeHeight, k.eye.y);
  if (path.eyeHeight == PathHeight::AboveLowest)
    eyeY = std::max(eyeY, ground + kGroundClearance * extent);
  else
    eyeY = std::max(eyeY, ground + kMinEyeAglSpacings * spacing);
  pose.eye.y = float(eyeY);
  pose.target.y = float(height(path.targetHeight, k.target.y));
  return pose;
}

}  // namespace

CameraPose samplePose(const CameraPath& path, double fps, int frame, const Heightfield& terrain) {
  checkFps(fps);
  if (path.keys.empty()) throw InputError(path.file + ": camera path has no keyframes");
  const Keyframe k = interpolate(path, path.keys.front().time + frame / fps);
  CameraPose pose = path.extentOnly() ? extentPose(k, terrain) : groundPose(path, k, terrain);
  if (terrain.originX != 0.0 || terrain.originZ != 0.0) {
    // Placed in double, then rounded to float like the patch vertices (renderer_setup.cpp).
    const glm::dvec3 o(terrain.originX, 0.0, terrain.originZ);
    pose.eye = glm::vec3(glm::dvec3(pose.eye) + o);
    pose.target = glm::vec3(glm::dvec3(pose.target) + o);
  }
  return pose;
}

}  // namespace lb
