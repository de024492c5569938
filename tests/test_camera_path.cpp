#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "camera/camera_path.h"
#include "error.h"
#include "terrain/heightfield.h"

namespace lb {
namespace {

const char* const kHeader = "time,eye_x,eye_y,eye_z,target_x,target_y,target_z,fov\n";

const std::string kGood = std::string("# a comment line\n") + kHeader +
                          "0,   0.1, 0.5, 0.2,  0.5, 0.1, 0.5, 60\n"
                          "# between keys\n"
                          "2.5, 0.3, 0.4, 0.4,  0.7, 0.1, 0.7, 50\n"
                          "4,   0.6, 0.3, 0.5,  0.9, 0.1, 0.9, 40\n"
                          "7,   0.9, 0.2, 0.8,  1.2, 0.1, 1.2, 70\n";

// Parses text expected to be rejected and returns the message.
std::string errorOf(const std::string& text, const std::string& name = "paths/bad.csv") {
  try {
    parseCameraPath(text, name);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return {};
}

void expectMentions(const std::string& msg, const std::string& line, const std::string& field) {
  EXPECT_NE(msg.find("paths/bad.csv:" + line + ":"), std::string::npos) << msg;
  EXPECT_NE(msg.find(field), std::string::npos) << msg;
}

void expectVec(const glm::dvec3& a, const glm::dvec3& b) {
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.z, b.z);
}

TEST(CameraPath, ParsesGoodCsv) {
  const CameraPath p = parseCameraPath(kGood, "good.csv");
  EXPECT_EQ(p.file, "good.csv");
  ASSERT_EQ(p.keys.size(), 4u);
  EXPECT_EQ(p.keys[1].time, 2.5);
  expectVec(p.keys[1].eye, {0.3, 0.4, 0.4});
  expectVec(p.keys[3].target, {1.2, 0.1, 1.2});
  EXPECT_EQ(p.keys[2].fovDeg, 40.0);
  EXPECT_DOUBLE_EQ(p.duration(), 7.0);
}

TEST(CameraPath, ToleratesCrlfBlankLinesAndReorderedColumns) {
  const CameraPath p = parseCameraPath(
      "fov,time,eye_x,eye_y,eye_z,target_x,target_y,target_z\r\n45,0,0.1,0.2,0.3,0.4,0.5,0.6\r\n\r\n"
      "50,+1,0.2,0.2,0.3,0.4,0.5,0.6\r\n",
      "crlf.csv");
  ASSERT_EQ(p.keys.size(), 2u);
  EXPECT_EQ(p.keys[0].fovDeg, 45.0);
  EXPECT_EQ(p.keys[1].time, 1.0);
  expectVec(p.keys[0].target, {0.4, 0.5, 0.6});
}

TEST(CameraPath, InterpolationHitsKeysExactly) {
  const CameraPath p = parseCameraPath(kGood, "good.csv");
  for (const Keyframe& k : p.keys) {
    const Keyframe i = interpolate(p, k.time);
    expectVec(i.eye, k.eye);
    expectVec(i.target, k.target);
    EXPECT_EQ(i.fovDeg, k.fovDeg);
  }
}

TEST(CameraPath, TwoKeyMidpointIsLinearMidpoint) {
  const CameraPath p =
      parseCameraPath(std::string(kHeader) + "1,0.2,0.4,0.1,0.6,0.2,0.9,40\n3,0.6,0.2,0.5,1.0,0.0,0.7,80\n", "two.csv");
  const Keyframe m = interpolate(p, 2.0);
  EXPECT_NEAR(m.eye.x, 0.4, 1e-12);
  EXPECT_NEAR(m.eye.y, 0.3, 1e-12);
  EXPECT_NEAR(m.eye.z, 0.3, 1e-12);
  EXPECT_NEAR(m.target.x, 0.8, 1e-12);
  EXPECT_NEAR(m.target.y, 0.1, 1e-12);
  EXPECT_NEAR(m.target.z, 0.8, 1e-12);
  EXPECT_NEAR(m.fovDeg, 60.0, 1e-12);
  EXPECT_NEAR(interpolate(p, 1.5).fovDeg, 50.0, 1e-12);  // fov is linear everywhere
}

TEST(CameraPath, CollinearConstantSpeedKeysGiveLinearInterior) {
  // Uneven key spacing, but positions proportional to time: the time-weighted tangents must
  // reproduce the straight constant-speed motion between the interior keys.
  const CameraPath p = parseCameraPath(std::string(kHeader) +
                                           "0,0.0,0.5,0.0,1,0.5,1,60\n1,0.1,0.5,0.05,1,0.5,1,60\n"
                                           "4,0.4,0.5,0.2,1,0.5,1,60\n5,0.5,0.5,0.25,1,0.5,1,60\n",
                                       "line.csv");
  for (double t = 1.0; t <= 4.0; t += 0.25) {
    const Keyframe k = interpolate(p, t);
    EXPECT_NEAR(k.eye.x, 0.1 * t, 1e-12) << t;
    EXPECT_NEAR(k.eye.z, 0.05 * t, 1e-12) << t;
  }
}

TEST(CameraPath, VelocityContinuousAcrossUnevenKeys) {
  const CameraPath p = parseCameraPath(kGood, "good.csv");
  const double h = 1e-5;
  for (size_t i = 1; i + 1 < p.keys.size(); ++i) {
    const double t = p.keys[i].time;
    const glm::dvec3 before = (interpolate(p, t).eye - interpolate(p, t - h).eye) / h;
    const glm::dvec3 after = (interpolate(p, t + h).eye - interpolate(p, t).eye) / h;
    EXPECT_LT(glm::length(after - before), 1e-3) << "key " << i;
  }
}

TEST(CameraPath, ClampsTimeToPath) {
  const CameraPath p = parseCameraPath(kGood, "good.csv");
  expectVec(interpolate(p, -100).eye, p.keys.front().eye);
  expectVec(interpolate(p, 1e9).eye, p.keys.back().eye);
  EXPECT_EQ(interpolate(p, 1e9).fovDeg, p.keys.back().fovDeg);
}

TEST(CameraPath, FrameCount) {
  const CameraPath p = parseCameraPath(kGood, "good.csv");  // 7 s
  EXPECT_EQ(frameCount(p, 60), 421);
  EXPECT_EQ(frameCount(p, 1), 8);
  EXPECT_EQ(frameCount(p, 0.5), 4);
  const CameraPath tenth = parseCameraPath(std::string(kHeader) + "0,0,1,0,1,0,1,60\n0.7,1,1,0,1,0,1,60\n", "t.csv");
  EXPECT_EQ(frameCount(tenth, 10), 8);  // 0.7 * 10 = 6.9999999999999991 without the epsilon
  EXPECT_THROW(frameCount(p, 0), InputError);
  EXPECT_THROW(frameCount(p, -30), InputError);
}

TEST(CameraPath, MalformedInputsNameFileLineAndField) {
  const std::string h = kHeader;
  const std::string row0 = "0,0.1,0.5,0.2,0.5,0.1,0.5,60\n";
  expectMentions(errorOf(h + row0 + "1,0.2,abc,0.2,0.5,0.1,0.5,60\n"), "3", "column 'eye_y': 'abc' is not a number");
  expectMentions(errorOf(h + row0 + "1,0.2,0.5,0.2,0.5,0.1\n"), "3", "target_z");
  expectMentions(errorOf(h + row0 + "1,0.2,0.5,0.2,0.5,0.1,0.5,60,7\n"), "3", "9 values");
  expectMentions(errorOf(h + row0 + "1,0.2,,0.2,0.5,0.1,0.5,60\n"), "3", "eye_y");
  expectMentions(errorOf("# c\ntime,eye_x,eye_y,eye_z,target_x,target_y,target_z,fovy\n" + row0), "2", "fovy");
  expectMentions(errorOf("time,eye_x,eye_y,eye_z,target_x,target_y,target_z\n" + row0), "1", "fov");
  expectMentions(errorOf(h + row0 + "# gap\n0,0.2,0.5,0.2,0.5,0.1,0.5,60\n"), "4", "column 'time'");
  expectMentions(errorOf(h + "1,0.2,0.5,0.2,0.5,0.1,0.5,60\n# comment\n"), "3", "at least 2");
  expectMentions(errorOf(""), "1", "empty");
  expectMentions(errorOf("# only a comment\n"), "1", "header");
  expectMentions(errorOf(h), "1", "at least 2");
  expectMentions(errorOf(h + row0 + "1,0.2,0.5,0.2,0.5,0.1,0.5,170\n"), "3", "column 'fov'");
  expectMentions(errorOf(h + row0 + "1,0.2,0.5,0.2,0.5,0.1,0.5,1\n"), "3", "column 'fov'");
  expectMentions(errorOf(h + row0 + "1,0.5,0.1,0.5,0.5,0.1,0.5,60\n"), "3", "target");
  expectMentions(errorOf(h + row0 + "1,0.2,inf,0.2,0.5,0.1,0.5,60\n"), "3", "column 'eye_y': 'inf' is not finite");
  expectMentions(errorOf(h + row0 + "1,0.2,nan,0.2,0.5,0.1,0.5,60\n"), "3", "column 'eye_y'");
  expectMentions(errorOf(h + row0 + "1,250,0.5,0.2,0.5,0.1,0.5,60\n"), "3", "column 'eye_x'");
  expectMentions(errorOf(h + row0 + "1,0.2,0.5,0.2,0.5,0.1,-3,60\n"), "3", "column 'target_z'");
  expectMentions(errorOf(h + row0 + "1,0.2,11,0.2,0.5,0.1,0.5,60\n"), "3", "column 'eye_y'");
}

TEST(CameraPath, MissingFile) {
  const std::string file = "/nonexistent/lodbench/path.csv";
  try {
    loadCameraPath(file);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot open camera path " + file), std::string::npos) << e.what();
  }
}

// 2x2 heightfield over 100 world units; the real bilinear sample() is linked in the full build.
Heightfield tinyTerrain() {
  Heightfield hf;
  hf.width = hf.height = 2;
  hf.extent = 100.0f;
  hf.h = {-5.0f, 5.0f, 15.0f, 25.0f};  // row-major, row = z: the centre is 10
  hf.minHeight = -5.0f;
  hf.maxHeight = 25.0f;
  return hf;
}

TEST(CameraPath, SamplePoseConvertsAndClampsToGround) {
  const Heightfield hf = tinyTerrain();
  // Eye at the centre: 0.05 -> 5 - 5 = 0 world, below ground (10), so clamped to 10 + 0.002 * 100.
  // Second key 0.5 -> 45 world, well above the ground. Targets below ground stay unclamped.
  const CameraPath p =
      parseCameraPath(std::string(kHeader) + "0,0.5,0.05,0.5,1,-0.5,1,50\n2,0.5,0.5,0.5,0,-0.5,0,70\n", "g.csv");
  const CameraPose low = samplePose(p, 10, 0, hf);
  EXPECT_FLOAT_EQ(low.eye.x, 50.0f);
  EXPECT_FLOAT_EQ(low.eye.z, 50.0f);
  EXPECT_NEAR(low.eye.y, 10.2f, 1e-4);
  EXPECT_FLOAT_EQ(low.target.x, 100.0f);
  EXPECT_FLOAT_EQ(low.target.y, -55.0f);
  EXPECT_FLOAT_EQ(low.fovDeg, 50.0f);

  const CameraPose high = samplePose(p, 10, 20, hf);  // t = 2 s, the last key
  EXPECT_FLOAT_EQ(high.eye.y, 45.0f);
  EXPECT_FLOAT_EQ(high.target.z, 0.0f);
  EXPECT_FLOAT_EQ(high.fovDeg, 70.0f);
  EXPECT_EQ(frameCount(p, 10), 21);
  EXPECT_THROW(samplePose(p, 0, 0, hf), InputError);
}

// A binary file named as a path must not echo raw bytes (escape sequences, NULs) to the terminal.
TEST(CameraPath, BinaryInputIsQuotedEscapedAndCut) {
  const std::string h = "time,eye_x,eye_y,eye_z,target_x,target_y,target_z,fov\n";
  std::string junk = "\x1b[31m\x01\xff" + std::string(200, 'z');
  const std::string e1 = errorOf(h + "0,0.2,0.5,0.2,0.5,0.1,0.5,60\n1," + junk + ",0.5,0.2,0.5,0.1,0.5,60\n");
  EXPECT_EQ(e1.find('\x1b'), std::string::npos) << e1;
  EXPECT_NE(e1.find("'\\x1b[31m\\x01\\xff"), std::string::npos) << e1;
  EXPECT_NE(e1.find("bytes)"), std::string::npos) << "long values are cut: " << e1;
  const std::string e2 = errorOf(junk + ",x\n");
  EXPECT_EQ(e2.find('\x1b'), std::string::npos) << e2;
  EXPECT_NE(e2.find("header"), std::string::npos) << e2;
}

// The frame rate is a flag or config field, not part of the CSV: its message must not blame the file.
TEST(CameraPath, BadFrameRateDoesNotBlameTheFile) {
  const CameraPath p =
      parseCameraPath(std::string(kHeader) + "0,0.5,0.5,0.5,1,0,1,50\n2,0.5,0.5,0.5,0,0,0,70\n", "g.csv");
  try {
    frameCount(p, 0);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).find("g.csv"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("fps"), std::string::npos) << e.what();
  }
}

// Scale-free columns: heights above the ground under the eye in sample spacings (or extents) and
// horizontal steps in spacings, against a terrain whose ground is known exactly.
const char* const kGroundHeader =
    "time,eye_x,eye_z,eye_dx_sp,eye_dz_sp,eye_agl_sp,target_x,target_z,target_dx_sp,target_agl_sp,fov\n";

// A plane rising along x: height = slope * world x (bilinear sampling is exact on it).
Heightfield rampTerrain(int samples, float extent, float slope) {
  Heightfield hf;
  hf.width = hf.height = samples;
  hf.extent = extent;
  hf.h.resize(size_t(samples) * size_t(samples));
  for (int z = 0; z < samples; ++z)
    for (int x = 0; x < samples; ++x) hf.h[size_t(z) * samples + x] = slope * extent * float(x) / float(samples - 1);
  hf.updateRange();
  return hf;
}

TEST(CameraPath, ParsesScaleFreeColumnsInAnyOrder) {
  const CameraPath p = parseCameraPath(std::string("# ground walk\n") + kGroundHeader +
                                           "0, 0.5,0.5, 0,0, 2, 0.9,0.9, 0, 2, 60\n"
                                           "10, 0.5,0.5, 14,-1, 2.5, 0.9,0.9, 14, 2, 60\n",
                                       "walk.csv");
  EXPECT_EQ(p.eyeHeight, PathHeight::SpacingsAboveGround);
  EXPECT_EQ(p.targetHeight, PathHeight::SpacingsAboveGround);
  EXPECT_TRUE(p.spacingSteps);
  EXPECT_FALSE(p.extentOnly());
  ASSERT_EQ(p.keys.size(), 2u);
  expectVec(p.keys[1].eye, {0.5, 2.5, 0.5});
  expectVec(p.keys[1].eyeStepSp, {14, 0, -1});
  expectVec(p.keys[1].targetStepSp, {14, 0, 0});  // no target_dz_sp column: 0
  const CameraPath agl = parseCameraPath(
      "fov,target_agl,target_z,target_x,eye_agl,eye_z,eye_x,time\n60,0,0.9,0.9,0.01,0.1,0.1,0\n"
      "60,0,0.95,0.95,0.01,0.2,0.2,3\n",
      "agl.csv");
  EXPECT_EQ(agl.eyeHeight, PathHeight::AboveGround);
  EXPECT_FALSE(agl.spacingSteps);
  EXPECT_TRUE(parseCameraPath(kGood, "good.csv").extentOnly());
}

TEST(CameraPath, ScaleFreeColumnsNameFileLineAndColumn) {
  const std::string h = kGroundHeader;
  const std::string row0 = "0,0.5,0.5,0,0,2,0.9,0.9,0,2,60\n";
  expectMentions(errorOf(h + row0 + "1,0.5,0.5,1,0,-1,0.9,0.9,0,2,60\n"), "3", "column 'eye_agl_sp': -1 is outside");
  expectMentions(errorOf(h + row0 + "1,0.5,0.5,x,0,2,0.9,0.9,0,2,60\n"), "3",
                 "column 'eye_dx_sp': 'x' is not a number");
  expectMentions(errorOf(h + row0 + "1,0.5,0.5,2e6,0,2,0.9,0.9,0,2,60\n"), "3", "column 'eye_dx_sp'");
  expectMentions(errorOf(h + row0 + "1,0.5,0.5,1,0,2,0.9,0.9,0,nan,60\n"), "3", "column 'target_agl_sp'");
  expectMentions(errorOf(h + row0 + "1,0.5,0.5,1,0,2,0.9,0.9,0,2\n"), "3", "column 'fov': missing (10 of 11 values)");
  expectMentions(errorOf("time,eye_x,eye_z,eye_agl,target_x,target_z,target_agl,fov\n0,0.5,0.5,11,0.9,0.9,0,60\n"), "2",
                 "column 'eye_agl': 11 is outside [0, 10] (eye_agl is in units of the extent above the ground");
  expectMentions(errorOf("time,eye_x,eye_z,target_x,target_y,target_z,fov\n" + row0), "1",
                 "header: missing column 'eye_y' (or 'eye_agl' or 'eye_agl_sp'");
  expectMentions(errorOf("time,eye_x,eye_z,eye_agl,eye_agl_sp,target_x,target_y,target_z,fov\n" + row0), "1",
                 "columns 'eye_agl' and 'eye_agl_sp' both give the eye's height");
  expectMentions(errorOf("time,eye_x,eye_z,eye_agl_sp,target_x,target_z,target_agl_sp,fov\n"
                         "0,0.5,0.5,2,0.5,0.5,2,60\n1,0.5,0.5,2,0.9,0.9,2,60\n"),
                 "2", "target equals the eye");
  expectMentions(errorOf("time,eye_x,eye_z,eye_agl_sp,eye_dy_sp,target_x,target_z,target_agl_sp,fov\n" + row0), "1",
                 "unexpected column 'eye_dy_sp'");
}

TEST(CameraPath, GroundRelativeHeightsFollowTheGroundInSpacings) {
  // 65 samples over 640 units: spacing 10; the ground rises 0.5 per unit of x.
  const Heightfield hf = rampTerrain(65, 640.0f, 0.5f);
  ASSERT_DOUBLE_EQ(sampleSpacing(hf), 10.0);
  const CameraPath p = parseCameraPath(std::string(kGroundHeader) +
                                           "0, 0.25,0.5, 0,0, 2, 0.75,0.5, 0, 2, 60\n"
                                           "10, 0.25,0.5, 14,0, 2, 0.75,0.5, 14, 2, 60\n",
                                       "walk.csv");
  for (int f : {0, 7, 30, 100}) {
    const CameraPose pose = samplePose(p, 10, f, hf);
    const double ground = hf.sample(pose.eye.x, pose.eye.z);
    EXPECT_NEAR(pose.eye.y - ground, 2 * 10.0, 1e-4) << f;     // eye_agl_sp 2: 20 units above the ground
    EXPECT_NEAR(pose.target.y - ground, 2 * 10.0, 1e-4) << f;  // same reference: a level gaze
  }
  // 14 spacings in 10 s: half way (the spline is symmetric there) and at the last key.
  EXPECT_FLOAT_EQ(samplePose(p, 10, 50, hf).eye.x, 160.0f + 70.0f);
  EXPECT_FLOAT_EQ(samplePose(p, 10, 100, hf).eye.x, 160.0f + 140.0f);
  // Below the clamp: the eye stays kMinEyeAglSpacings (1) spacing above the ground, the target does not.
  const CameraPath low = parseCameraPath(std::string(kGroundHeader) +
                                             "0, 0.5,0.5, 0,0, 0.25, 0.75,0.5, 0, -3, 60\n"
                                             "1, 0.5,0.5, 0,0, 0, 0.75,0.5, 0, -3, 60\n",
                                         "low.csv");
  for (int f : {0, 10}) {
    const CameraPose pose = samplePose(low, 10, f, hf);
    EXPECT_NEAR(pose.eye.y, 160.0f + kMinEyeAglSpacings * 10.0, 1e-4) << f;
    EXPECT_NEAR(pose.target.y, 160.0f - 30.0f, 1e-4) << f;  // 3 spacings below the ground under the eye
  }
  // eye_agl in extents: 0.03 x 640 above the ground (0.01 would be under the 1-spacing clamp).
  const CameraPath agl = parseCameraPath(
      "time,eye_x,eye_z,eye_agl,target_x,target_z,target_y,fov\n0,0.5,0.5,0.03,0.9,0.5,0,60\n1,0.5,0.5,0.03,0.9,0.5,0,"
      "60\n",
      "agl.csv");
  const CameraPose a = samplePose(agl, 10, 5, hf);
  EXPECT_NEAR(a.eye.y, 160.0f + 19.2f, 1e-4);
  EXPECT_FLOAT_EQ(a.target.y, hf.minHeight);
  // A far origin moves the pose, not the ground lookup.
  Heightfield far = hf;
  far.originX = 1e6;
  const CameraPose moved = samplePose(p, 10, 30, far), here = samplePose(p, 10, 30, hf);
  EXPECT_FLOAT_EQ(moved.eye.y, here.eye.y);
  EXPECT_FLOAT_EQ(moved.eye.x, float(double(here.eye.x) + 1e6));
}

// The point of the columns: one path, terrains of very different extents and sample counts, the
// same motion and height counted in spacings.
TEST(CameraPath, SpacingColumnsAreScaleFree) {
  const CameraPath p = parseCameraPath(std::string(kGroundHeader) +
                                           "0, 0.3,0.4, 0,0, 2, 0.8,0.9, 0, 2, 60\n"
                                           "4, 0.3,0.4, 3,4, 3, 0.8,0.9, 3, 2, 60\n"
                                           "8, 0.3,0.4, 9,6, 2, 0.8,0.9, 9, 2, 60\n",
                                       "walk.csv");
  const Heightfield small = rampTerrain(33, 64.0f, 0.3f), big = rampTerrain(257, 51200.0f, 0.05f);
  const double sSmall = sampleSpacing(small), sBig = sampleSpacing(big);
  for (int f = 0; f < frameCount(p, 10); ++f) {
    const CameraPose a = samplePose(p, 10, f, small), b = samplePose(p, 10, f, big);
    const double aglA = (a.eye.y - small.sample(a.eye.x, a.eye.z)) / sSmall;
    const double aglB = (b.eye.y - big.sample(b.eye.x, b.eye.z)) / sBig;
    ASSERT_NEAR(aglA, aglB, 1e-4) << f;
    ASSERT_GE(aglA, 2.0 - 1e-4) << f;
    ASSERT_NEAR((a.eye.x - 0.3 * 64.0) / sSmall, (b.eye.x - 0.3 * 51200.0) / sBig, 1e-4) << f;
    ASSERT_NEAR((a.eye.z - 0.4 * 64.0) / sSmall, (b.eye.z - 0.4 * 51200.0) / sBig, 1e-4) << f;
  }
}

class ShippedPath : public ::testing::TestWithParam<const char*> {};

TEST_P(ShippedPath, ParsesAndStaysOverTerrain) {
  const CameraPath p = loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/" + GetParam());
  EXPECT_GE(p.duration(), 5.0);
  const double fps = 60;
  const int frames = frameCount(p, fps);
  for (int f = 0; f < frames; ++f) {
    const Keyframe k = interpolate(p, p.keys.front().time + f / fps);
    ASSERT_TRUE(k.eye.x >= 0 && k.eye.x <= 1 && k.eye.z >= 0 && k.eye.z <= 1) << "frame " << f;
    ASSERT_GT(glm::length(k.target - k.eye), 0.01) << "frame " << f;
  }
}

INSTANTIATE_TEST_SUITE_P(Configs, ShippedPath, ::testing::Values("flyover.csv", "lowalt.csv", "horizon.csv"));

}  // namespace
}  // namespace lb
