#include "schemes/registry.h"

#include "did_you_mean.h"

namespace lb {

// Each scheme file defines one factory; adding a scheme = its declaration here and its line in the table.
const Scheme& uniformScheme();
const Scheme& sphereScheme();
const Scheme& interlockScheme();
const Scheme& sphereRingsScheme();
const Scheme& densityScheme();
const Scheme& phongScheme();
const Scheme& distanceScheme();
const Scheme& referenceScheme();
const Scheme& planeFitScheme();
const Scheme& errBoundScheme();
const Scheme& sphereEdgeScheme();
const Scheme& cdlodScheme();
const Scheme& cdlodSseScheme();
const Scheme& clipmapScheme();
const Scheme& chunkedScheme();
const Scheme& clustersScheme();
const Scheme& clustersMsScheme();
const Scheme& cbtScheme();
const Scheme& cbtTsScheme();
const Scheme& uniformCullScheme();
const Scheme& sphereMsScheme();
const Scheme& cdlodMsScheme();
const Scheme& cbtMsScheme();

static std::vector<const Scheme*>& registered() {
  static std::vector<const Scheme*> schemes = {
      // One scheme a line, so that adding one is one line of a diff.
      // clang-format off
      &uniformScheme(),
      &sphereScheme(),
      &interlockScheme(),
      &sphereRingsScheme(),
      &densityScheme(),
      &phongScheme(),
      &distanceScheme(),
      &referenceScheme(),
      &planeFitScheme(),
      &errBoundScheme(),
      &sphereEdgeScheme(),
      &cdlodScheme(),
      &cdlodSseScheme(),
      &clipmapScheme(),
      &cbtScheme(),
      &cbtTsScheme(),
      &uniformCullScheme(),
      // Mesh-shader twins (DrawPath::Mesh): skipped, with the reason, on devices without VK_EXT_mesh_shader.
      &sphereMsScheme(),
      &cdlodMsScheme(),
      &cbtMsScheme(),
      // Precomputed irregular meshes (after the twins, so every earlier scheme keeps its chart style).
      &chunkedScheme(),
      &clustersScheme(),
      &clustersMsScheme(),
      // clang-format on
  };
  return schemes;
}

const std::vector<const Scheme*>& allSchemes() {
  return registered();
}

void addPluginScheme(const Scheme& scheme) {
  registered().push_back(&scheme);
}

TuneSpace defaultTuneSpace(const Scheme& scheme) {
  const SchemeInfo& info = scheme.info();
  TuneSpace space;
  // Patches per side decide how fine a tessellation scheme can go at all (level 64 x grid cells a
  // side): 16 is coarse for a 4097^2 terrain, 256 reaches 16385^2 at level 64.
  if (drawsPatchGrid(info) && !info.mainParam.empty()) space["grid"] = {16, 64, 256};
  // What a user of each method sets besides its main knob (the sources' constants, as ranges).
  // Finer cells than samples are what a close view of a coarse DEM needs to follow its bilinear
  // surface (an H100 run found cdlod-sse and cbt unable to reach 1 px on a 90 m crop's grazing
  // view at one cell a sample); node size and leaf subdivision trade draws against culling.
  static const std::map<std::string, TuneSpace> kExtra = {
      {"interlock", {{"min_lod", {1, 4}}}},                                // the book's minMaxLOD.x
      {"cdlod", {{"node_cells", {16, 64}}, {"cells_per_texel", {1, 2}}}},  // Strugar's node size, grid
      {"cdlod-sse", {{"node_cells", {16, 64}}, {"cells_per_texel", {1, 2}}}},
      {"clipmap", {{"cells_per_texel", {1, 2}}}},                // the finest level's spacing
      {"cbt", {{"subd", {2, 3}}, {"cells_per_texel", {1, 2}}}},  // LEB2D's leaf subdivision, depth
      {"cbt-ts", {{"subd", {2, 3}}, {"cells_per_texel", {1, 2}}}},
      // The finest chunks' simplification error (sample spacings): at its default 0.1 chunked could
      // not reach 1 px on a 90 m tile's ground and grazing views at 1080p (an H200 run: 7.6 and
      // 2.9 px at its finest max_error_px); at 0.001 the grazing view reads 0.36 px, the ground
      // view 1.3 px (its finest mesh is the sample grid, which a bilinear surface seen that close
      // outruns: the lattice schemes tune cells_per_texel for it).
      {"chunked", {{"leaf_error", {0.001, 0.1}}}},
      // The mesh twins tune what their twins tune.
      {"cdlod-ms", {{"node_cells", {16, 64}}, {"cells_per_texel", {1, 2}}}},
      {"cbt-ms", {{"subd", {2, 3}}, {"cells_per_texel", {1, 2}}}},
  };

  auto extra = kExtra.find(info.name);
  if (extra != kExtra.end())
    for (const auto& [k, v] : extra->second)
      if (k != info.mainParam) space[k] = v;
  return space;
}

const Scheme& sphereCopyScheme();
const Scheme& sphereTwiceScheme();

const std::vector<const Scheme*>& controlSchemes() {
  static const std::vector<const Scheme*> schemes = {&sphereCopyScheme(), &sphereTwiceScheme()};
  return schemes;
}

const Scheme* findScheme(const std::string& name) {
  for (const Scheme* s : allSchemes())
    if (s->info().name == name) return s;
  for (const Scheme* s : controlSchemes())
    if (s->info().name == name) return s;
  return nullptr;
}

const std::vector<std::string>& schemeGroupNames() {
  static const std::vector<std::string> names = {"all",          "tessellation", "instanced-grid",
                                                 "gpu-indirect", "mesh",         "controls"};
  return names;
}

std::vector<const Scheme*> schemeGroup(const std::string& group) {
  if (group == "controls") return controlSchemes();
  std::vector<const Scheme*> out;
  for (const Scheme* s : allSchemes()) {
    const DrawPath path = s->info().path;
    if (group == "all" || (group == "tessellation" && path == DrawPath::Tessellation) ||
        (group == "instanced-grid" && path == DrawPath::InstancedGrid) ||
        (group == "gpu-indirect" && path == DrawPath::GpuIndirect) || (group == "mesh" && path == DrawPath::Mesh))
      out.push_back(s);
  }
  return out;
}

const Scheme* schemeWithRole(MainParamRole role) {
  for (const Scheme* s : allSchemes())
    if (s->info().mainParamRole == role && !s->info().mainParam.empty()) return s;
  return nullptr;
}

std::string schemeNames() {
  std::string out;
  for (const Scheme* s : allSchemes()) out += (out.empty() ? "" : ", ") + s->info().name;
  return out;
}

std::string unknownSchemeText(const std::string& name) {
  std::vector<std::string> names;
  for (const Scheme* s : allSchemes()) names.push_back(s->info().name);
  return "unknown scheme '" + name + "' (known: " + schemeNames() + ")" + didYouMean(name, names);
}

}  // namespace lb
