// Bad-input table: every row is one distinct bad input (config, camera path, terrain
// file or command line) run through the lodbench binary. Each must exit 2 before any case runs,
// with a message naming the file and line (or the flag) and the field, and must leave an existing
// run directory exactly as it was.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "cli_run.h"

namespace fs = std::filesystem;

namespace {

const std::string kGoodCsv =
    "time,eye_x,eye_y,eye_z,target_x,target_y,target_z,fov\n"
    "0,0.1,0.3,0.1,0.5,0,0.5,60\n"
    "1,0.9,0.3,0.9,0.5,0,0.5,60\n";  // 31 frames at 30 fps

struct Row {
  const char* name;
  std::map<std::string, std::string> files;  // written into the row's directory
  std::string args;                          // ${D}: the row's directory, ${R}: the existing run
  std::vector<std::string> expect;           // substrings of the output (file:line, field, flag)
  int code = 2;
};

// A config whose line 6 is `extra` (after a comma): errors there must name "c.json:6".
std::string cfg(const std::string& extra) {
  return "{\n  \"name\": \"bad\",\n  \"paths\": [\"ok.csv\"],\n  \"resolution\": [16, 16],\n  \"schemes\": "
         "[\"uniform\"],\n  " +
         extra + "\n}\n";
}
std::string cfgTerrain(const std::string& terrain) {
  return cfg("\"terrain\": " + terrain);
}
std::string cfgPath(const std::string& path) {
  return "{\n  \"name\": \"bad\",\n  \"paths\": [\"" + path + "\"],\n  \"schemes\": [\"uniform\"]\n}\n";
}
std::string cfgScheme(const std::string& scheme) {
  return "{\n  \"paths\": [\"ok.csv\"],\n  \"schemes\": [\n    " + scheme + "\n  ]\n}\n";
}
std::string csv(const std::string& rows) {
  return "time,eye_x,eye_y,eye_z,target_x,target_y,target_z,fov\n" + rows;
}

std::string le16(std::initializer_list<uint16_t> v) {
  std::string s;
  for (uint16_t x : v) s += char(x & 0xff), s += char(x >> 8);
  return s;
}
std::string le32f(std::initializer_list<float> v) {
  std::string s;
  for (float f : v) {
    char b[4];
    std::memcpy(b, &f, 4);
    s.append(b, 4);
  }
  return s;
}

const std::string kRun = "run ${D}/c.json --out ${R} --quiet";
const std::string kRender = "render --width 16 --height 16 --grid 2 ";
const std::string kPathArg =
    "--path ${D}/ok.csv --out ${R}/render.png ";  // a render that wrongly ran would change ${R}

std::vector<Row> rows() {
  const std::string nan32 = le32f({0.0f, 1.0f, std::numeric_limits<float>::quiet_NaN(), 2.0f});
  return {
      // --- config fields
      {"grid_zero", {{"c.json", cfg("\"grid\": 0")}}, kRun, {"c.json:6", "field '/grid'", "[1, 1024]"}},
      {"grid_string", {{"c.json", cfg("\"grid\": \"big\"")}}, kRun, {"c.json:6", "'/grid'", "expected a number"}},
      {"fps_zero", {{"c.json", cfg("\"fps\": 0")}}, kRun, {"c.json:6", "'/fps'"}},
      {"warmup_negative", {{"c.json", cfg("\"warmup_frames\": -1")}}, kRun, {"c.json:6", "'/warmup_frames'"}},
      {"max_frames_fraction", {{"c.json", cfg("\"max_frames\": 1.5")}}, kRun, {"c.json:6", "'/max_frames'", "integer"}},
      {"repetitions_zero", {{"c.json", cfg("\"repetitions\": 0")}}, kRun, {"c.json:6", "'/repetitions'"}},
      {"timeout_negative", {{"c.json", cfg("\"case_timeout_s\": -1")}}, kRun, {"c.json:6", "'/case_timeout_s'"}},
      {"unknown_key", {{"c.json", cfg("\"gird\": 8")}}, kRun, {"c.json:6", "'/gird'", "unknown key"}},
      {"duplicate_key", {{"c.json", cfg("\"grid\": 8, \"grid\": 16")}}, kRun, {"c.json:6", "'/grid'", "duplicate key"}},
      {"duplicate_nested_key",
       {{"c.json", cfgTerrain("{\"type\": \"procedural\",\n  \"seed\": 1, \"seed\": 2}")}},
       kRun,
       {"c.json:7", "'/terrain/seed'", "duplicate key"}},
      {"name_with_slash",
       {{"c.json", "{\n \"name\": \"a/b\",\n \"paths\": [\"ok.csv\"], \"schemes\": [\"uniform\"]}"}},
       kRun,
       {"c.json:2", "'/name'"}},
      {"device_number", {{"c.json", cfg("\"device\": 5")}}, kRun, {"c.json:6", "'/device'", "expected a string"}},
      {"resolution_small", {{"c.json", cfg("\"resolutions\": [[10, 10]]")}}, kRun, {"c.json:6", "'/resolutions/0/0'"}},
      {"resolution_one_number", {{"c.json", cfg("\"resolutions\": [[16]]")}}, kRun, {"c.json:6", "'/resolutions/0'"}},
      {"resolution_huge",
       {{"c.json", cfg("\"resolutions\": [[16, 16], [20000, 16]]")}},
       kRun,
       {"c.json:6", "'/resolutions/1/0'"}},
      {"resolutions_duplicate",
       {{"c.json", cfg("\"resolutions\": [[16, 16],\n    [16, 16]]")}},
       kRun,
       {"c.json:7", "'/resolutions/1'", "resolution #1 (16x16; /resolutions/0, line 6) and #2 (16x16) are the same"}},
      // --- terrains
      {"terrain_type",
       {{"c.json", cfgTerrain("{\"type\": \"tiff\"}")}},
       kRun,
       {"c.json:6", "'/terrain/type'", "'tiff'"}},
      {"terrain_no_file",
       {{"c.json", cfgTerrain("{\"type\": \"hgt\"}")}},
       kRun,
       {"c.json:6", "'/terrain'", "needs a 'file'"}},
      {"terrain_file_missing",
       {{"c.json", cfgTerrain("{\"type\": \"hgt\", \"file\": \"none.hgt\"}")}},
       kRun,
       {"c.json:6", "'/terrain/file'", "none.hgt"}},
      {"terrain_file_directory",
       {{"c.json", cfgTerrain("{\"type\": \"hgt\", \"file\": \".\"}")}},
       kRun,
       {"c.json:6", "'/terrain/file'", "is a directory"}},
      {"procedural_with_file",
       {{"c.json", cfgTerrain("{\"type\": \"procedural\", \"file\": \"ok.csv\"}")}},
       kRun,
       {"c.json:6", "'/terrain/file'", "does not use 'file'"}},
      {"png16_with_width",
       {{"t.png", "x"}, {"c.json", cfgTerrain("{\"type\": \"png16\", \"file\": \"t.png\", \"width\": 4}")}},
       kRun,
       {"c.json:6", "'/terrain/width'", "does not use 'width'"}},
      {"png16_with_seed",
       {{"t.png", "x"}, {"c.json", cfgTerrain("{\"type\": \"png16\", \"file\": \"t.png\", \"seed\": 4}")}},
       kRun,
       {"c.json:6", "'/terrain/seed'", "does not use 'seed'"}},
      {"hgt_with_size",
       {{"t.hgt", "x"}, {"c.json", cfgTerrain("{\"type\": \"hgt\", \"file\": \"t.hgt\", \"size\": 65}")}},
       kRun,
       {"c.json:6", "'/terrain/size'", "does not use 'size'"}},
      {"r16_no_dimensions",
       {{"t.r16", le16({1, 2, 3, 4})}, {"c.json", cfgTerrain("{\"type\": \"r16\", \"file\": \"t.r16\"}")}},
       kRun,
       {"c.json:6", "'/terrain'", "'width' and 'height'"}},
      {"r16_size_mismatch",
       {{"t.r16", le16({1, 2, 3})},
        {"c.json", cfgTerrain("{\"type\": \"r16\", \"file\": \"t.r16\", \"width\": 2, \"height\": 2}")}},
       kRun,
       {"c.json:6", "'/terrain/file'", "t.r16: expected 2*2*2 = 8 bytes, got 6"}},
      {"r32f_huge_heights",
       {{"t.r32f", le32f({0.0f, 1e30f, -1e30f, 1.0f})},
        {"c.json", cfgTerrain("{\"type\": \"r32f\", \"file\": \"t.r32f\", \"width\": 2, \"height\": 2}")}},
       kRun,
       {"c.json:6", "'/terrain/file'", "sample (1, 0)", "+-1e5", "5x Earth's relief"}},
      {"r32f_nan",
       {{"t.r32f", nan32},
        {"c.json", cfgTerrain("{\"type\": \"r32f\", \"file\": \"t.r32f\", \"width\": 2, \"height\": 2}")}},
       kRun,
       {"c.json:6", "'/terrain/file'", "sample (0, 1) is not a finite number"}},
      {"r16_scaled_too_high",
       {{"t.r16", le16({0, 1, 2, 65535})},
        {"c.json",
         cfgTerrain("{\"type\": \"r16\", \"file\": \"t.r16\", \"width\": 2, \"height\": 2, \"height_scale\": 10}")}},
       kRun,
       {"c.json:6", "'/terrain/file'", "sample (1, 1)", "+-1e5"}},
      {"hgt_wrong_size",
       {{"t.hgt", std::string(100, '\0')}, {"c.json", cfgTerrain("{\"type\": \"hgt\", \"file\": \"t.hgt\"}")}},
       kRun,
       {"c.json:6", "'/terrain/file'", "t.hgt: size 100 bytes"}},
      // Past lavapipe's maxImageDimension2D (16384): refused from the spec, before generating it.
      {"terrain_past_device_limit",
       {{"c.json", cfgTerrain("{\"type\": \"procedural\", \"size\": 16385}")}},
       "run ${D}/c.json --out ${D}/new --quiet",
       {"terrain 'proc16385s1'", "16385 x 16385 samples", "maxImageDimension2D", "a 'size' of at most"}},
      {"render_terrain_past_device_limit",
       {},
       kRender + kPathArg + "--size 16385",
       {"16385 x 16385 samples", "maxImageDimension2D"}},
      {"png16_not_png",
       {{"t.png", "not a png"}, {"c.json", cfgTerrain("{\"type\": \"png16\", \"file\": \"t.png\"}")}},
       kRun,
       {"c.json:6", "'/terrain/file'", "t.png: cannot decode PNG"}},
      {"procedural_height_scale",
       {{"c.json", cfgTerrain("{\"type\": \"procedural\", \"height_scale\": 1e6}")}},
       kRun,
       {"c.json:6", "'/terrain/height_scale'", "[0, 100000]"}},
      {"extent_zero", {{"c.json", cfgTerrain("{\"extent\": 0}")}}, kRun, {"c.json:6", "'/terrain/extent'"}},
      {"seed_list_empty",
       {{"c.json", cfgTerrain("{\"seed\": []}")}},
       kRun,
       {"c.json:6", "'/terrain/seed'", "empty list"}},
      {"terrains_not_array", {{"c.json", cfg("\"terrains\": {\"seed\": 1}")}}, kRun, {"c.json:6", "'/terrains'"}},
      // An empty list beside the single form is refused like an empty "paths".
      {"terrains_empty_beside_terrain",
       {{"c.json", cfg("\"terrain\": {\"size\": 17},\n  \"terrains\": []")}},
       kRun,
       {"c.json:7", "'/terrains'", "non-empty array"}},
      {"terrains_duplicate",
       {{"c.json", cfg("\"terrains\": [{\"size\": 17},\n    {\"size\": 17}]")}},
       kRun,
       {"c.json:7", "'/terrains/1'", "terrain #1 (proc17s1; /terrains/0, line 6) and #2", "are the same"}},
      // --- camera paths named by a config: found before any case, with the CSV's own line
      {"path_missing", {{"c.json", cfgPath("none.csv")}}, kRun, {"c.json:3", "'/paths/0'", "none.csv"}},
      {"path_directory", {{"c.json", cfgPath(".")}}, kRun, {"c.json:3", "'/paths/0'", "is a directory"}},
      {"paths_not_array",
       {{"c.json", "{\n \"paths\": \"ok.csv\",\n \"schemes\": [\"uniform\"]}"}},
       kRun,
       {"c.json:2", "'/paths'"}},
      {"no_paths", {{"c.json", "{\n \"schemes\": [\"uniform\"]\n}"}}, kRun, {"c.json", "no camera path"}},
      {"paths_empty",
       {{"c.json", "{\n \"paths\": [],\n \"schemes\": [\"uniform\"]\n}"}},
       kRun,
       {"c.json:2", "'/paths'", "non-empty array"}},
      {"paths_empty_beside_path",
       {{"c.json", "{\n \"path\": \"ok.csv\",\n \"paths\": [],\n \"schemes\": [\"uniform\"]\n}"}},
       kRun,
       {"c.json:3", "'/paths'", "non-empty array"}},
      {"paths_duplicate",
       {{"c.json", "{\n \"path\": \"ok.csv\",\n \"paths\": [\"./ok.csv\"],\n \"schemes\": [\"uniform\"]\n}"}},
       kRun,
       {"c.json:3", "'/paths/0'", "camera path #1", "/path, line 2) and #2", "are the same"}},
      {"csv_keyframes_too_close",
       {{"p.csv", csv("0,0.1,0.3,0.1,0.5,0,0.5,60\n1e-300,0.2,0.3,0.1,0.5,0,0.5,60\n")}, {"c.json", cfgPath("p.csv")}},
       kRun,
       {"c.json:3", "'/paths/0'", "p.csv:3", "column 'time'", "previous keyframe's 0 (line 2)",
        "at least 1e-6 s apart"}},
      {"csv_keyframes_under_a_microsecond",
       {{"p.csv", csv("0,0.1,0.3,0.1,0.5,0,0.5,60\n1,0.2,0.3,0.1,0.5,0,0.5,60\n1.0000009,0.3,0.3,0.1,0.5,0,0.5,60\n")},
        {"c.json", cfgPath("p.csv")}},
       kRun,
       {"p.csv:4", "column 'time'", "at least 1e-6 s apart"}},
      {"csv_not_a_number",
       {{"p.csv", csv("0,0.1,0.3,0.1,0.5,0,0.5,60\n1,abc,0.3,0.9,0.5,0,0.5,60\n")}, {"c.json", cfgPath("p.csv")}},
       kRun,
       {"c.json:3", "'/paths/0'", "p.csv:3", "column 'eye_x'", "'abc' is not a number"}},
      {"csv_binary",
       {{"p.csv", std::string("\x01\x02\xff\xfe\x1b[31mgarbage\x00\x03,x\n", 20)}, {"c.json", cfgPath("p.csv")}},
       kRun,
       {"c.json:3", "p.csv:1", "\\x01\\x02\\xff\\xfe\\x1b"}},
      {"csv_header",
       {{"p.csv", "t,x,y,z,tx,ty,tz,fov\n0,0,0,0,1,0,1,60\n"}, {"c.json", cfgPath("p.csv")}},
       kRun,
       {"p.csv:1", "header"}},
      {"csv_missing_value",
       {{"p.csv", csv("0,0.1,0.3,0.1,0.5,0,0.5,60\n1,0.2,0.3,0.1,0.5,0,0.5\n")}, {"c.json", cfgPath("p.csv")}},
       kRun,
       {"p.csv:3", "column 'fov': missing"}},
      {"csv_time_not_increasing",
       {{"p.csv", csv("0,0.1,0.3,0.1,0.5,0,0.5,60\n0,0.2,0.3,0.1,0.5,0,0.5,60\n")}, {"c.json", cfgPath("p.csv")}},
       kRun,
       {"p.csv:3", "column 'time'", "strictly increase"}},
      {"csv_one_keyframe",
       {{"p.csv", csv("0,0.1,0.3,0.1,0.5,0,0.5,60\n")}, {"c.json", cfgPath("p.csv")}},
       kRun,
       {"p.csv:", "at least 2"}},
      {"csv_empty", {{"p.csv", ""}, {"c.json", cfgPath("p.csv")}}, kRun, {"p.csv:1", "file is empty"}},
      {"csv_fov_zero",
       {{"p.csv", csv("0,0.1,0.3,0.1,0.5,0,0.5,0\n1,0.2,0.3,0.1,0.5,0,0.5,60\n")}, {"c.json", cfgPath("p.csv")}},
       kRun,
       {"p.csv:2", "column 'fov'"}},
      {"csv_eye_y_range",
       {{"p.csv", csv("0,0.1,50,0.1,0.5,0,0.5,60\n1,0.2,0.3,0.1,0.5,0,0.5,60\n")}, {"c.json", cfgPath("p.csv")}},
       kRun,
       {"p.csv:2", "column 'eye_y'", "50 is outside"}},
      {"csv_target_is_eye",
       {{"p.csv", csv("0,0.5,0.3,0.5,0.5,0.3,0.5,60\n1,0.2,0.3,0.1,0.5,0,0.5,60\n")}, {"c.json", cfgPath("p.csv")}},
       kRun,
       {"p.csv:2", "target equals the eye"}},
      // Scale-free columns (ground-relative heights, steps in sample spacings): the same file:line:column.
      {"csv_agl_sp_negative",
       {{"p.csv",
         "time,eye_x,eye_z,eye_agl_sp,target_x,target_z,target_agl_sp,fov\n0,0.5,0.5,2,0.9,0.9,2,60\n"
         "1,0.5,0.5,-3,0.9,0.9,2,60\n"},
        {"c.json", cfgPath("p.csv")}},
       kRun,
       {"c.json:3", "'/paths/0'", "p.csv:3", "column 'eye_agl_sp'", "-3 is outside [0, 1000000]",
        "sample spacings above the ground under the eye"}},
      {"csv_dx_sp_not_a_number",
       {{"p.csv",
         "time,eye_x,eye_z,eye_dx_sp,eye_agl_sp,target_x,target_z,target_agl_sp,fov\n"
         "0,0.5,0.5,0,2,0.9,0.9,2,60\n1,0.5,0.5,1.4m,2,0.9,0.9,2,60\n"},
        {"c.json", cfgPath("p.csv")}},
       kRun,
       {"p.csv:3", "column 'eye_dx_sp'", "'1.4m' is not a number"}},
      {"csv_two_eye_heights",
       {{"p.csv",
         "# walk\ntime,eye_x,eye_y,eye_z,eye_agl_sp,target_x,target_y,target_z,fov\n"
         "0,0.5,0.1,0.5,2,0.9,0,0.9,60\n1,0.5,0.1,0.5,2,0.9,0,0.9,60\n"},
        {"c.json", cfgPath("p.csv")}},
       kRun,
       {"p.csv:2", "header: columns 'eye_y' and 'eye_agl_sp' both give the eye's height"}},
      {"csv_no_target_height",
       {{"p.csv", "time,eye_x,eye_z,eye_agl_sp,target_x,target_z,fov\n0,0.5,0.5,2,0.9,0.9,60\n"},
        {"c.json", cfgPath("p.csv")}},
       kRun,
       {"p.csv:1", "header: missing column 'target_y' (or 'target_agl' or 'target_agl_sp'"}},
      // --- schemes and parameters
      {"schemes_empty",
       {{"c.json", "{\n \"paths\": [\"ok.csv\"],\n \"schemes\": []\n}"}},
       kRun,
       {"c.json:3", "'/schemes'"}},
      {"scheme_unknown",
       {{"c.json", cfgScheme("\"nope\"")}},
       kRun,
       {"c.json:4", "'/schemes/0'", "unknown scheme 'nope'"}},
      {"param_out_of_range",
       {{"c.json", cfgScheme("{\"name\": \"sphere\", \"params\": {\"tri_size\": 0}}")}},
       kRun,
       {"c.json:4", "'/schemes/0/params/tri_size'"}},
      {"param_unknown",
       {{"c.json", cfgScheme("{\"name\": \"uniform\", \"params\": {\"lvl\": 2}}")}},
       kRun,
       {"c.json:4", "'/schemes/0/params/lvl'", "no parameter 'lvl'"}},
      {"param_not_integer",
       {{"c.json", cfgScheme("{\"name\": \"uniform\", \"params\": {\"level\": 2.5}}")}},
       kRun,
       {"c.json:4", "'/schemes/0/params/level'", "integer"}},
      {"param_list_empty",
       {{"c.json", cfgScheme("{\"name\": \"uniform\", \"params\": {\"level\": []}}")}},
       kRun,
       {"c.json:4", "'/schemes/0/params/level'", "empty list"}},
      {"params_not_object",
       {{"c.json", cfgScheme("{\"name\": \"uniform\", \"params\": [1]}")}},
       kRun,
       {"c.json:4", "'/schemes/0/params'"}},
      {"scheme_duplicate",
       {{"c.json", cfgScheme("\"uniform\",\n    \"uniform\"")}},
       kRun,
       {"c.json:5", "'/schemes/1'", "/schemes/0 (line 4) and /schemes/1 both run uniform (defaults)"}},
      {"scheme_default_listed_beside_left_out",
       {{"c.json", cfgScheme("\"cdlod\",\n    {\"name\": \"cdlod\", \"params\": {\"morph\": 0.3}}")}},
       kRun,
       {"c.json:5", "'/schemes/1'", "/schemes/0 (line 4) and /schemes/1 both run cdlod", "morph=0.3"}},
      {"distance_empty_range",
       {{"c.json", cfgScheme("{\"name\": \"distance\", \"params\": {\"dmin\": 0.5, \"dmax\": 0.5}}")}},
       kRun,
       {"c.json:4", "'/schemes/0/params'", "dmin"}},
      {"interlock_empty_range",
       {{"c.json", cfgScheme("{\"name\": \"interlock\", \"params\": {\"dmin\": 0.5, \"dmax\": 0.5}}")}},
       kRun,
       {"c.json:4", "'/schemes/0/params'", "dmin"}},
      // --- images, measurement, matching
      {"image_frame_past_end",
       {{"c.json", cfg("\"images\": {\"frames\": [0, 31]}")}},
       kRun,
       {"c.json:6", "'/images/frames/1'", "31 frames"}},
      {"image_frame_before_start",
       {{"c.json", cfg("\"images\": {\"frames\": [-32]}")}},
       kRun,
       {"c.json:6", "'/images/frames/0'"}},
      {"image_frame_past_max_frames",
       {{"c.json", cfg("\"max_frames\": 10, \"images\": {\"frames\": [10]}")}},
       kRun,
       {"c.json:6", "'/images/frames/0'", "10 frames"}},
      {"image_mode",
       {{"c.json", cfg("\"images\": {\"modes\": [\"sepia\"]}")}},
       kRun,
       {"c.json:6", "'/images/modes/0'"}},
      {"image_modes_not_array",
       {{"c.json", cfg("\"images\": {\"modes\": \"shaded\"}")}},
       kRun,
       {"c.json:6", "'/images/modes'"}},
      {"images_unknown_key", {{"c.json", cfg("\"images\": {\"frame\": [0]}")}}, kRun, {"c.json:6", "'/images/frame'"}},
      {"measure_pass",
       {{"c.json", cfg("\"measure\": {\"passes\": [\"ssim\"]}")}},
       kRun,
       {"c.json:6", "'/measure/passes/0'"}},
      {"measure_every", {{"c.json", cfg("\"measure\": {\"every\": -1}")}}, kRun, {"c.json:6", "'/measure/every'"}},
      {"match_metric",
       {{"c.json", cfg("\"match\": {\"metric\": \"fps\", \"value\": 3}")}},
       kRun,
       {"c.json:6", "'/match/metric'"}},
      {"match_no_value", {{"c.json", cfg("\"match\": {\"metric\": \"triangles\"}")}}, kRun, {"c.json:6", "'/match'"}},
      // --- the config file itself
      {"json_truncated",
       {{"c.json", "{\n \"paths\": [\"ok.csv\"],\n \"schemes\": [\"uniform\"\n"}},
       kRun,
       {"c.json:4", "invalid JSON"}},
      {"json_number_overflow",
       {{"c.json", cfg("\"grid\": 3e999999")}},
       kRun,
       {"c.json", "invalid JSON", "number overflow"}},
      {"json_top_level_array", {{"c.json", "[1, 2]"}}, kRun, {"c.json", "expected an object"}},
      {"config_directory", {}, "run ${D} --out ${R} --quiet", {"is a directory"}},
      {"config_missing", {}, "run ${D}/none.json --out ${R} --quiet", {"none.json"}},
      // --- command line
      {"unknown_subcommand", {}, "frobnicate", {"unknown subcommand 'frobnicate'", "render"}},
      {"no_subcommand", {}, "", {"Usage", "Subcommands"}},
      {"device_unmatched",
       {{"c.json", cfg("\"grid\": 2")}},
       "run ${D}/c.json --out ${D}/new --quiet --device nomatch",
       {"--device 'nomatch'"}},
      // A config's device names the config's file, line and field, not a flag that was not given.
      {"config_device_unmatched",
       {{"c.json", cfg("\"device\": \"nomatch\"")}},
       "run ${D}/c.json --out ${D}/new --quiet",
       {"c.json:6: field '/device': no suitable Vulkan device matches 'nomatch'"}},
      // The flag overrides the config's device, and its message names the flag.
      {"device_flag_over_config_device",
       {{"c.json", cfg("\"device\": \"nomatch\"")}},
       "run ${D}/c.json --out ${D}/new --quiet --device nomatch2",
       {"--device 'nomatch2'"}},
      {"shard_out_of_range", {{"c.json", cfg("\"grid\": 2")}}, kRun + " --shard 3/2", {"--shard '3/2'"}},
      {"render_height_scale_nan", {}, kRender + kPathArg + "--height-scale nan", {"--height-scale", "nan"}},
      {"render_fps_zero", {}, kRender + kPathArg + "--fps 0", {"--fps"}},
      {"render_out_missing_dir",
       {},
       kRender + "--path ${D}/ok.csv --out /nonexistent-dir/x.png",
       {"--out", "does not exist"}},
      {"render_out_directory", {}, kRender + "--path ${D}/ok.csv --out ${D}", {"--out", "is a directory"}},
      {"render_raw_no_size",
       {{"t.r16", le16({1, 2, 3, 4})}},
       kRender + kPathArg + "--terrain r16 --terrain-file ${D}/t.r16",
       {"--terrain-width", "--terrain-height"}},
      {"render_raw_size_on_png",
       {{"t.png", "x"}},
       kRender + kPathArg + "--terrain png16 --terrain-file ${D}/t.png --terrain-width 2 --terrain-height 2",
       {"--terrain-width"}},
      {"render_file_type_no_file", {}, kRender + kPathArg + "--terrain hgt", {"--terrain-file"}},
      {"render_procedural_with_file", {}, kRender + kPathArg + "--terrain-file ${D}/ok.csv", {"--terrain-file"}},
      {"render_terrain_type", {}, kRender + kPathArg + "--terrain tiff", {"--terrain 'tiff'"}},
      {"render_r32f_huge",
       {{"t.r32f", le32f({0.0f, 1e30f, -1e30f, 1.0f})}},
       kRender + kPathArg + "--terrain r32f --terrain-file ${D}/t.r32f --terrain-width 2 --terrain-height 2",
       {"t.r32f: sample (1, 0)", "+-1e5"}},
      {"render_bad_csv",
       {{"p.csv", csv("0,0.1,0.3,0.1,0.5,0,0.5,60\n1,0.2,x,0.1,0.5,0,0.5,60\n")}},
       kRender + "--out ${R}/render.png --path ${D}/p.csv",
       {"p.csv:3", "column 'eye_y'"}},
      {"render_scheme", {}, kRender + kPathArg + "--scheme nope", {"--scheme", "unknown scheme 'nope'"}},
      {"render_param", {}, kRender + kPathArg + "--param tri_size=abc", {"--param 'tri_size=abc'"}},
      {"render_frame", {}, kRender + kPathArg + "--frame 31", {"--frame 31", "31 frames"}},
      {"render_extent", {}, kRender + kPathArg + "--extent 0", {"--extent"}},
      {"render_device", {}, kRender + kPathArg + "--device nomatch", {"--device 'nomatch'"}},
  };
}

std::string substitute(std::string s, const std::string& dir, const std::string& run) {
  for (auto [key, value] : {std::make_pair(std::string("${D}"), dir), std::make_pair(std::string("${R}"), run)})
    for (size_t p; (p = s.find(key)) != std::string::npos;) s.replace(p, key.size(), value);
  return s;
}

// Every file under dir with its bytes: a bad invocation must change none and add none.
std::map<std::string, std::string> snapshot(const std::string& dir) {
  std::map<std::string, std::string> out;
  for (auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) {
      std::ifstream in(e.path(), std::ios::binary);
      out[e.path().string()] = std::string(std::istreambuf_iterator<char>(in), {});
    }
  return out;
}

}  // namespace

TEST(BadInput, EveryRowExitsTwoNamingTheInputAndWritesNothing) {
  const std::string root = lb::test::freshDir("bad_input");
  const std::string run = root + "/existing-run";
  // A finished run the bad invocations are pointed at (--out): it must come out byte for byte unchanged.
  const std::string good = root + "/good.json";
  fs::create_directories(root);
  std::ofstream(root + "/ok.csv") << kGoodCsv;
  std::ofstream(good) << "{\"name\": \"good\", \"paths\": [\"ok.csv\"], \"resolution\": [16, 16], \"grid\": 2,"
                         " \"warmup_frames\": 0, \"max_frames\": 2, \"terrain\": {\"size\": 17},"
                         " \"schemes\": [{\"name\": \"uniform\", \"params\": {\"level\": 1}}]}";
  lb::test::CliOut first = lb::test::lodbench("run " + good + " --out " + run + " --quiet", false);
  ASSERT_EQ(first.code, 0) << first.text;
  const auto before = snapshot(run);
  ASSERT_FALSE(before.empty());

  const std::vector<Row> table = rows();
  EXPECT_GE(table.size(), 60u);
  std::set<std::string> names;
  for (const Row& row : table) {
    SCOPED_TRACE(row.name);
    EXPECT_TRUE(names.insert(row.name).second) << "duplicate row name";
    const std::string dir = root + "/" + row.name;
    fs::create_directories(dir);
    std::ofstream(dir + "/ok.csv") << kGoodCsv;
    for (auto& [file, content] : row.files) std::ofstream(dir + "/" + file, std::ios::binary) << content;
    const std::string args = substitute(row.args, dir, run);
    lb::test::CliOut o = lb::test::lodbench(args, false);
    EXPECT_EQ(o.code, row.code) << "lodbench " << args << "\n" << o.text;
    for (const std::string& e : row.expect)
      EXPECT_NE(o.text.find(substitute(e, dir, run)), std::string::npos)
          << "missing '" << e << "' in the output of lodbench " << args << "\n"
          << o.text;
    // Raw control bytes of a binary input never reach the terminal.
    EXPECT_EQ(o.text.find('\x1b'), std::string::npos) << o.text;
    EXPECT_TRUE(snapshot(run) == before) << "the existing run directory changed";
    EXPECT_FALSE(fs::exists(dir + "/new")) << "a run directory was created before the error";
  }
}
