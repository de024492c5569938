#version 450
#extension GL_GOOGLE_include_directive : require
// practical-d3d11-ch9 9.1.2 "Pre-Processing the Height Map", Listings 9.10-9.16: one 16x16
// workgroup per heightmap block writes (plane normal, coplanarity) to the lookup texture. fit = 0
// follows the listings (transcription errors fixed, see schemes/preprocess/plane_fit.cpp), fit = 1
// is the corrected least-squares version. schemes/preprocess/plane_fit.cpp is the CPU reference: keep
// the arithmetic and its order identical.
#define LB_COMPUTE_PASS
#include "shared.h"
#include "planefit_params.h"
#include "heights.glsl"

float computeParam(int i) { return pass.params[i / 4][i % 4]; }

layout(local_size_x = LB_PLANE_FIT_BLOCK, local_size_y = LB_PLANE_FIT_BLOCK) in;
layout(set = 0, binding = LB_BINDING_SCHEME_IMAGE, rgba32f) uniform writeonly image2D lookup;

const int kB = LB_PLANE_FIT_BLOCK;
const int kLast = kB - 1;
const int kN = kB * kB;

// Listing 9.11's group-shared state, plus the block mean of the least-squares fit.
shared float groupResults[kN];
shared vec4 plane;
shared vec3 rawNormals[2][2];
shared vec3 corners[2][2];
shared float blockMean;

bool leastSquares() { return computeParam(LB_PLANEFIT_FIT) > 0.5; }

// Block-centred sample position in world units (least-squares fit).
vec2 centredXZ(int gi) {
  vec2 spacing = pass.terrain.x / vec2(max(terrainSamples() - 1, ivec2(1)));
  return (vec2(gi % kB, gi / kB) - 7.5) * spacing;
}

// Listing 9.14: average corner normal, plane through the lowest corner.
vec4 bookPlane() {
  vec3 n = normalize(rawNormals[0][0] + rawNormals[0][1] + rawNormals[1][0] + rawNormals[1][1]);
  vec3 p = vec3(0.0, 1e9, 0.0);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      if (corners[i][j].y < p.y) p = corners[i][j];
  return vec4(n, -n.x * p.x - n.y * p.y - n.z * p.z);  // CreatePlaneFromPointAndNormal
}

// Least squares y = a + b x + c z; centred x, z make the normal equations decouple.
vec4 leastSquaresPlane() {
  float sy = 0.0;
  for (int gi = 0; gi < kN; ++gi) sy += groupResults[gi];
  float mean = sy / float(kN);
  float sxy = 0.0, szy = 0.0, sxx = 0.0, szz = 0.0;
  for (int gi = 0; gi < kN; ++gi) {
    vec2 xz = centredXZ(gi);
    float y = groupResults[gi] - mean;
    sxy += xz.x * y;
    szy += xz.y * y;
    sxx += xz.x * xz.x;
    szz += xz.y * xz.y;
  }
  blockMean = mean;
  return vec4(normalize(vec3(-sxy / sxx, 1.0, -szy / szz)), 0.0);
}

void main() {
  ivec2 g = ivec2(gl_LocalInvocationID.xy);
  int gi = int(gl_LocalInvocationIndex);
  // Phase one (Listing 9.12): load; blocks past the border repeat the last sample.
  ivec2 src = min(ivec2(gl_GlobalInvocationID.xy), terrainSamples() - 1);
  float h = heightAt(src);
  bool lsq = leastSquares();
  if (!lsq) {
    // The book reads a UNORM height texture: heights in [0, 1].
    float range = pass.terrain.w > pass.terrain.z ? pass.terrain.w - pass.terrain.z : 1.0;
    h = (h - pass.terrain.z) / range;
  }
  groupResults[gi] = h;
  bool corner = (g.x == 0 || g.x == kLast) && (g.y == 0 || g.y == kLast);
  if (corner) corners[g.x / kLast][g.y / kLast] = vec3(float(g.x / kLast) / 64.0, h, float(g.y / kLast) / 64.0);
  barrier();

  // Phase two (Listing 9.13): a normal per corner from its two neighbouring corners.
  if (g == ivec2(0, 0))
    rawNormals[0][0] = normalize(cross(corners[0][1] - corners[0][0], corners[1][0] - corners[0][0]));
  else if (g == ivec2(kLast, 0))
    rawNormals[1][0] = normalize(cross(corners[0][0] - corners[1][0], corners[1][1] - corners[1][0]));
  else if (g == ivec2(0, kLast))
    rawNormals[0][1] = normalize(cross(corners[1][1] - corners[0][1], corners[0][0] - corners[0][1]));
  else if (g == ivec2(kLast, kLast))
    rawNormals[1][1] = normalize(cross(corners[1][0] - corners[1][1], corners[0][1] - corners[1][1]));
  barrier();

  // Phase three (Listing 9.14): one thread decides the plane.
  if (gi == 0) plane = lsq ? leastSquaresPlane() : bookPlane();
  barrier();

  // Phase four (Listing 9.15): each thread replaces its height by its distance to the plane.
  if (lsq) {
    vec2 xz = centredXZ(gi);
    groupResults[gi] = dot(plane.xyz, vec3(xz.x, h - blockMean, xz.y));
  } else {
    groupResults[gi] = dot(plane.xyz, vec3(float(g.x) / 15.0, h, float(g.y) / 15.0)) + plane.w;
  }
  barrier();

  // Phase five (Listing 9.16): one thread reduces to the standard deviation and writes the texel.
  if (gi == 0) {
    float deviation;
    if (lsq) {
      float sd = 0.0;
      for (int i = 0; i < kN; ++i) sd += groupResults[i];
      float dMean = sd / float(kN);
      float var = 0.0;
      for (int i = 0; i < kN; ++i) {
        float d = groupResults[i] - dMean;
        var += d * d;
      }
      deviation = sqrt(var / float(kN));
    } else {
      float sum = 0.0;
      for (int i = 0; i < kN; ++i) sum += groupResults[i] * groupResults[i];
      deviation = sqrt(sum / (float(kN) - 1.0));
    }
    imageStore(lookup, ivec2(gl_WorkGroupID.xy), vec4(plane.xyz, deviation));
  }
}
