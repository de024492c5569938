#include <gtest/gtest.h>
#include <stb/stb_image_write.h>  // implementation lives in the library (harness/render/image_io.cpp)

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "dem_crop.h"
#include "error.h"
#include "input_error.h"
#include "terrain/heightfield.h"

using lb::Heightfield;
using lb::InputError;
using lb::TerrainSpec;

namespace {

std::string tempPath(const std::string& name) {
  return ::testing::TempDir() + "lodbench_terrain_" + name;
}

void writeBytes(const std::string& path, const std::vector<unsigned char>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  ASSERT_TRUE(out.good()) << path;
}

using lbtest::inputErrorOf;

template <class Vector>
uint64_t fnv1a(const Vector& v) {
  uint64_t hash = 1469598103934665603ull;
  for (float f : v) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    for (int k = 0; k < 4; ++k) hash = (hash ^ ((u >> (8 * k)) & 0xffu)) * 1099511628211ull;
  }
  return hash;
}

// --- Minimal 16-bit grayscale PNG writer (stb_image_write only does 8-bit): zlib stored blocks.
uint32_t crc32(const unsigned char* p, size_t n, uint32_t crc = 0) {
  crc = ~crc;
  for (size_t i = 0; i < n; ++i) {
    crc ^= p[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void putBe32(std::vector<unsigned char>& out, uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back((unsigned char)(v >> s));
}

void putChunk(std::vector<unsigned char>& png, const char* type, const std::vector<unsigned char>& data) {
  putBe32(png, uint32_t(data.size()));
  std::vector<unsigned char> body(type, type + 4);
  body.insert(body.end(), data.begin(), data.end());
  png.insert(png.end(), body.begin(), body.end());
  putBe32(png, crc32(body.data(), body.size()));
}

std::vector<unsigned char> png16Gray(int w, int h, const std::vector<uint16_t>& px) {
  std::vector<unsigned char> raw;  // filter byte 0 + big-endian samples per row
  for (size_t i = 0; i < px.size(); ++i) {
    if (i % size_t(w) == 0) raw.push_back(0);
    raw.push_back((unsigned char)(px[i] >> 8)), raw.push_back((unsigned char)px[i]);
  }
  std::vector<unsigned char> z = {0x78, 0x01};
  for (size_t pos = 0; pos < raw.size();) {
    const size_t n = std::min<size_t>(65535, raw.size() - pos);
    z.push_back(pos + n == raw.size() ? 1 : 0);
    z.push_back((unsigned char)n), z.push_back((unsigned char)(n >> 8));
    z.push_back((unsigned char)~n), z.push_back((unsigned char)(~n >> 8));
    z.insert(z.end(), raw.begin() + long(pos), raw.begin() + long(pos + n));
    pos += n;
  }
  uint32_t a = 1, b = 0;
  for (unsigned char c : raw) a = (a + c) % 65521, b = (b + a) % 65521;
  putBe32(z, b << 16 | a);
  std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<unsigned char> ihdr;
  putBe32(ihdr, uint32_t(w)), putBe32(ihdr, uint32_t(h));
  ihdr.insert(ihdr.end(), {16, 0, 0, 0, 0});  // 16-bit, grayscale, deflate, adaptive, no interlace
  putChunk(png, "IHDR", ihdr);
  putChunk(png, "IDAT", z);
  putChunk(png, "IEND", {});
  return png;
}

TerrainSpec proceduralSpec(int size, uint32_t seed) {
  TerrainSpec s;
  s.size = size, s.seed = seed, s.heightScale = 120.0f;
  return s;
}

TerrainSpec fileSpec(const std::string& type, const std::string& name) {
  TerrainSpec s;
  s.type = type, s.file = tempPath(name);
  return s;
}

// 3x2 field, extent 4: texel x = p / 4 * 2, texel z = p / 4.
Heightfield smallField() {
  Heightfield hf;
  hf.width = 3, hf.height = 2, hf.extent = 4.0f;
  hf.h = {1, 3, 7, 5, 11, 2};
  return hf;
}

// Heights of the synthetic .hgt, in metres; x = column (west->east), z = row (north->south).
int16_t hgtPattern(int x, int z) {
  return int16_t(x - 2 * z + 100);
}

}  // namespace

TEST(Terrain, ProceduralIsDeterministicPerSeed) {
  const Heightfield a = lb::makeProcedural(proceduralSpec(129, 7));
  const Heightfield b = lb::makeProcedural(proceduralSpec(129, 7));
  const Heightfield c = lb::makeProcedural(proceduralSpec(129, 8));
  ASSERT_EQ(a.h.size(), 129u * 129u);
  EXPECT_EQ(0, std::memcmp(a.h.data(), b.h.data(), a.h.size() * sizeof(float)));
  EXPECT_NE(0, std::memcmp(a.h.data(), c.h.data(), a.h.size() * sizeof(float)));
}

// Guards "same seed -> same bits on any machine/compiler". If the generator is changed on purpose,
// update the constant: every recorded result that used procedural terrain changes with it.
TEST(Terrain, ProceduralMatchesGoldenBits) {
  EXPECT_EQ(fnv1a(lb::makeProcedural(proceduralSpec(65, 1)).h), 0xab62627d31ea5915ull);
}

TEST(Terrain, ProceduralRangeAndShape) {
  TerrainSpec s = proceduralSpec(257, 3);
  s.extent = 5000.0f;
  const Heightfield hf = lb::makeProcedural(s);
  EXPECT_EQ(hf.width, 257);
  EXPECT_EQ(hf.height, 257);
  EXPECT_EQ(hf.extent, 5000.0f);
  float lo = hf.h[0], hi = hf.h[0];
  double mean = 0.0;
  for (float v : hf.h) lo = std::min(lo, v), hi = std::max(hi, v), mean += v;
  mean /= double(hf.h.size());
  EXPECT_EQ(lo, 0.0f);
  EXPECT_LE(hi, 120.0f);
  EXPECT_GE(hi, 119.99f);
  EXPECT_EQ(hf.minHeight, lo);
  EXPECT_EQ(hf.maxHeight, hi);
  // Mountains: mostly low ground with ridges, not a flat plate or a plateau.
  EXPECT_GT(mean, 0.15 * 120.0);
  EXPECT_LT(mean, 0.6 * 120.0);
}

TEST(Terrain, ProceduralRejectsBadSpec) {
  for (int size : {1, 32769, -5}) EXPECT_NE(inputErrorOf([&] { lb::makeProcedural(proceduralSpec(size, 1)); }), "");
  TerrainSpec s = proceduralSpec(64, 1);
  s.extent = 0.0f;
  EXPECT_NE(inputErrorOf([&] { lb::makeProcedural(s); }).find("extent"), std::string::npos);
  s.extent = 100.0f;
  for (float bad : {NAN, -1.0f}) {
    s.heightScale = bad;
    EXPECT_NE(inputErrorOf([&] { lb::makeProcedural(s); }).find("heightScale"), std::string::npos);
  }
  s.heightScale = 0.0f;  // a flat plane is allowed
  EXPECT_EQ(lb::makeProcedural(s).maxHeight, 0.0f);
}

TEST(Terrain, SampleAtGridPointsEqualsAt) {
  TerrainSpec s = proceduralSpec(257, 11);
  s.extent = 256.0f;  // one world unit per cell keeps the texel arithmetic exact
  const Heightfield hf = lb::makeProcedural(s);
  for (int z = 0; z < hf.height; z += 3)
    for (int x = 0; x < hf.width; x += 5) ASSERT_EQ(hf.sample(float(x), float(z)), hf.at(x, z)) << x << "," << z;
  EXPECT_EQ(hf.sample(256.0f, 256.0f), hf.at(256, 256));
  EXPECT_EQ(hf.sample(256.0f, 0.0f), hf.at(256, 0));
}

TEST(Terrain, SampleIsBilinear) {
  const Heightfield hf = smallField();
  EXPECT_EQ(hf.sample(1.0f, 0.0f), 2.0f);  // midpoint of 1 and 3
  EXPECT_EQ(hf.sample(0.0f, 2.0f), 3.0f);  // midpoint of 1 and 5
  EXPECT_EQ(hf.sample(1.0f, 2.0f), (1 + 3 + 5 + 11) / 4.0f);
  EXPECT_EQ(hf.sample(3.0f, 2.0f), (3 + 7 + 11 + 2) / 4.0f);
  EXPECT_EQ(hf.sample(0.5f, 0.0f), 1.5f);  // a quarter of the way from 1 to 3
}

TEST(Terrain, SampleAndAtClampAtBorders) {
  Heightfield hf = smallField();
  EXPECT_EQ(hf.at(-4, -1), 1.0f);
  EXPECT_EQ(hf.at(9, 9), 2.0f);
  EXPECT_EQ(hf.sample(-10.0f, -10.0f), 1.0f);
  EXPECT_EQ(hf.sample(1e6f, 1e6f), 2.0f);
  EXPECT_EQ(hf.sample(4.0f, -3.0f), 7.0f);
  EXPECT_EQ(hf.sample(-1.0f, 2.0f), 3.0f);  // x clamped to 0, z halfway
  EXPECT_EQ(hf.sample(NAN, NAN), 1.0f);
  hf.updateRange();
  EXPECT_EQ(hf.minHeight, 1.0f);
  EXPECT_EQ(hf.maxHeight, 11.0f);
}

TEST(Terrain, HgtLoadsOrientationAndFillsVoids) {
  const int n = 1201;
  std::vector<unsigned char> bytes(size_t(n) * n * 2);
  const std::vector<std::pair<int, int>> voids = {{600, 600}, {0, 0}, {100, 50}, {101, 50}, {102, 50}};
  for (int z = 0; z < n; ++z)
    for (int x = 0; x < n; ++x) {
      int16_t v = hgtPattern(x, z);
      for (auto [vx, vz] : voids)
        if (vx == x && vz == z) v = -32768;
      const size_t i = (size_t(z) * n + size_t(x)) * 2;
      bytes[i] = (unsigned char)(uint16_t(v) >> 8), bytes[i + 1] = (unsigned char)(uint16_t(v) & 0xff);
    }
  TerrainSpec s = fileSpec("hgt", "synthetic.hgt");
  s.extent = 108000.0f;
  s.heightScale = 0.5f;
  writeBytes(s.file, bytes);
  const Heightfield hf = lb::makeHeightfield(s);
  ASSERT_EQ(hf.width, n);
  ASSERT_EQ(hf.height, n);
  EXPECT_EQ(hf.extent, 108000.0f);
  auto m = [](int x, int z) { return float(hgtPattern(x, z)) * 0.5f; };
  // First file row is z = 0 (north), first column x = 0 (west).
  EXPECT_EQ(hf.at(1, 0), m(1, 0));
  EXPECT_EQ(hf.at(1200, 0), m(1200, 0));
  EXPECT_EQ(hf.at(0, 1200), m(0, 1200));
  EXPECT_EQ(hf.at(1200, 1200), m(1200, 1200));
  EXPECT_EQ(hf.at(37, 911), m(37, 911));
  EXPECT_EQ(hf.minHeight, m(0, 1200));
  EXPECT_EQ(hf.maxHeight, m(1200, 0));
  // A lone void takes the mean of its 4 neighbours (= the plane's value, exactly).
  EXPECT_EQ(hf.at(600, 600), m(600, 600));
  EXPECT_EQ(hf.at(0, 0), (m(1, 0) + m(0, 1)) / 2.0f);
  // A run of three: the ends fill first from their 3 valid neighbours, then the middle from them.
  const float left = (m(99, 50) + m(100, 49) + m(100, 51)) / 3.0f;
  const float right = (m(103, 50) + m(102, 49) + m(102, 51)) / 3.0f;
  EXPECT_EQ(hf.at(100, 50), left);
  EXPECT_EQ(hf.at(102, 50), right);
  EXPECT_EQ(hf.at(101, 50), (left + right + m(101, 49) + m(101, 51)) / 4.0f);
}

TEST(Terrain, HgtWrongSizeNamesFile) {
  TerrainSpec s = fileSpec("hgt", "bad_tile.hgt");
  writeBytes(s.file, std::vector<unsigned char>(1000, 0));
  const std::string msg = inputErrorOf([&] { lb::makeHeightfield(s); });
  EXPECT_NE(msg.find("bad_tile.hgt"), std::string::npos) << msg;
  EXPECT_NE(msg.find("1000 bytes"), std::string::npos) << msg;
}

TEST(Terrain, MissingFileNamesFile) {
  TerrainSpec s = fileSpec("png16", "does_not_exist.png");
  EXPECT_EQ(inputErrorOf([&] { lb::makeHeightfield(s); }), "cannot open " + s.file);
}

TEST(Terrain, Png16Roundtrip) {
  const int w = 5, h = 3;
  const std::vector<uint16_t> px = {0, 1, 2, 65535, 12345, 100, 200, 300, 400, 500, 32768, 7, 8, 9, 65534};
  TerrainSpec s = fileSpec("png16", "height16.png");
  s.heightScale = 0.5f;  // stored value x height_scale, like r16 and hgt (no division by 65535)
  s.extent = 640.0f;
  writeBytes(s.file, png16Gray(w, h, px));
  const Heightfield hf = lb::makeHeightfield(s);
  ASSERT_EQ(hf.width, w);
  ASSERT_EQ(hf.height, h);
  EXPECT_EQ(hf.extent, 640.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) EXPECT_EQ(hf.at(x, y), float(px[size_t(y * w + x)]) * 0.5f);
  EXPECT_EQ(hf.maxHeight, 65535.0f * 0.5f);
  EXPECT_EQ(hf.minHeight, 0.0f);
}

// The four file types agree: the same stored samples give the same heights.
TEST(Terrain, EveryFileTypeMeansStoredValueTimesHeightScale) {
  const std::vector<uint16_t> px = {0, 1, 258, 8848, 4096, 77};
  TerrainSpec png = fileSpec("png16", "same.png"), r16 = fileSpec("r16", "same.r16"),
              r32 = fileSpec("r32f", "same.r32f");
  writeBytes(png.file, png16Gray(3, 2, px));
  std::vector<unsigned char> b16, b32;
  for (uint16_t v : px) {
    b16.push_back((unsigned char)(v & 0xff)), b16.push_back((unsigned char)(v >> 8));
    const float f = float(v);
    uint32_t u;
    std::memcpy(&u, &f, 4);
    for (int k = 0; k < 4; ++k) b32.push_back((unsigned char)(u >> (8 * k)));
  }
  writeBytes(r16.file, b16);
  writeBytes(r32.file, b32);
  r16.rawWidth = r32.rawWidth = 3;
  r16.rawHeight = r32.rawHeight = 2;
  png.heightScale = r16.heightScale = r32.heightScale = 2.0f;
  const Heightfield a = lb::makeHeightfield(png), b = lb::makeHeightfield(r16), c = lb::makeHeightfield(r32);
  for (size_t i = 0; i < px.size(); ++i) {
    EXPECT_EQ(a.h[i], float(px[i]) * 2.0f) << i;
    EXPECT_EQ(b.h[i], a.h[i]) << i;
    EXPECT_EQ(c.h[i], a.h[i]) << i;
  }
}

// Heights beyond +-kMaxAbsHeight (after height_scale) are rejected, not rendered as a blank frame.
TEST(Terrain, AbsurdHeightsAreRejected) {
  auto r32With = [&](float v) {
    TerrainSpec s = fileSpec("r32f", "absurd.r32f");
    s.rawWidth = 2, s.rawHeight = 2, s.heightScale = 1.0f;
    const float vals[4] = {0.0f, 1.0f, v, 2.0f};
    std::vector<unsigned char> b(16);
    std::memcpy(b.data(), vals, 16);
    writeBytes(s.file, b);
    return s;
  };
  for (float v : {1e30f, -1e30f, 1.0001e5f}) {
    const std::string msg = inputErrorOf([&] { lb::makeHeightfield(r32With(v)); });
    EXPECT_NE(msg.find("sample (0, 1)"), std::string::npos) << msg;
    EXPECT_NE(msg.find("+-1e5"), std::string::npos) << msg;
  }
  EXPECT_EQ(lb::makeHeightfield(r32With(-1e5f)).minHeight, -1e5f);  // the bound itself is accepted
  TerrainSpec r16 = fileSpec("r16", "absurd.r16");
  r16.rawWidth = 2, r16.rawHeight = 2, r16.heightScale = 2.0f;  // 65535 x 2 > 1e5
  writeBytes(r16.file, std::vector<unsigned char>(8, 0xff));
  EXPECT_NE(inputErrorOf([&] { lb::makeHeightfield(r16); }).find("+-1e5"), std::string::npos);
  TerrainSpec proc = proceduralSpec(17, 1);
  proc.heightScale = 2e5f;
  EXPECT_NE(inputErrorOf([&] { lb::makeHeightfield(proc); }).find("1e5"), std::string::npos);
}

TEST(Terrain, Png8BitIsRejected) {
  TerrainSpec s = fileSpec("png16", "gray8.png");
  const unsigned char px[4 * 4] = {0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120, 130, 140, 150};
  ASSERT_NE(stbi_write_png(s.file.c_str(), 4, 4, 1, px, 4), 0);
  const std::string msg = inputErrorOf([&] { lb::makeHeightfield(s); });
  EXPECT_NE(msg.find(s.file + ": not a 16-bit grayscale PNG"), std::string::npos) << msg;
}

TEST(Terrain, RawR16AndR32fRoundtrip) {
  TerrainSpec s = fileSpec("r16", "h.r16");
  s.rawWidth = 3, s.rawHeight = 2, s.heightScale = 1.5f;
  const std::vector<uint16_t> v16 = {0, 1, 258, 65535, 4096, 77};
  std::vector<unsigned char> b16;
  for (uint16_t v : v16) b16.push_back((unsigned char)(v & 0xff)), b16.push_back((unsigned char)(v >> 8));
  writeBytes(s.file, b16);
  Heightfield hf = lb::makeHeightfield(s);
  ASSERT_EQ(hf.width, 3);
  ASSERT_EQ(hf.height, 2);
  for (size_t i = 0; i < v16.size(); ++i) EXPECT_EQ(hf.h[i], float(v16[i]) * 1.5f);
  EXPECT_EQ(hf.at(0, 1), 65535.0f * 1.5f);

  const std::vector<float> v32 = {-12.5f, 0.0f, 1e-3f, 3000.25f, 7.0f, -0.0f};
  std::vector<unsigned char> b32;
  for (float f : v32) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    for (int k = 0; k < 4; ++k) b32.push_back((unsigned char)(u >> (8 * k)));
  }
  s = fileSpec("r32f", "h.r32f");
  s.rawWidth = 3, s.rawHeight = 2, s.heightScale = 2.0f;
  writeBytes(s.file, b32);
  hf = lb::makeHeightfield(s);
  for (size_t i = 0; i < v32.size(); ++i) EXPECT_EQ(hf.h[i], v32[i] * 2.0f);
  EXPECT_EQ(hf.minHeight, -25.0f);
  EXPECT_EQ(hf.maxHeight, 6000.5f);
}

TEST(Terrain, RawSizeMismatchAndMissingDimensions) {
  TerrainSpec s = fileSpec("r16", "short.r16");
  s.rawWidth = 4, s.rawHeight = 4;
  writeBytes(s.file, std::vector<unsigned char>(30, 0));
  std::string msg = inputErrorOf([&] { lb::makeHeightfield(s); });
  EXPECT_NE(msg.find(s.file + ": expected 4*4*2 = 32 bytes, got 30"), std::string::npos) << msg;
  s.type = "r32f";
  msg = inputErrorOf([&] { lb::makeHeightfield(s); });
  EXPECT_NE(msg.find("expected 4*4*4 = 64 bytes, got 30"), std::string::npos) << msg;
  s.rawWidth = 0;
  msg = inputErrorOf([&] { lb::makeHeightfield(s); });
  EXPECT_NE(msg.find("--terrain-width"), std::string::npos) << msg;  // names options that exist
  EXPECT_NE(msg.find("'width'"), std::string::npos) << msg;
}

TEST(Terrain, UnknownTypeListsValidTypes) {
  TerrainSpec s;
  s.type = "tiff";
  const std::string msg = inputErrorOf([&] { lb::makeHeightfield(s); });
  EXPECT_NE(msg.find("'tiff'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("procedural, hgt, png16, r16, r32f, gdal"), std::string::npos) << msg;
}

// The committed crop (tests/data/README.md): columns and rows 600-1200 of N44W072, which hold both
// the tile's lowest (115 m) and highest (1908 m, Mount Washington) samples.
TEST(Terrain, RealSrtmCrop) {
  TerrainSpec s = lbtest::demCrop();
  s.heightScale = 1.0f;
  const Heightfield hf = lb::makeHeightfield(s);
  EXPECT_EQ(hf.width, 601);
  EXPECT_EQ(hf.height, 601);
  EXPECT_EQ(hf.minHeight, 115.0f);
  EXPECT_EQ(hf.maxHeight, 1908.0f);
  EXPECT_EQ(hf.at(0, 0), 313.0f);  // north-west corner is the first sample of the file
}
