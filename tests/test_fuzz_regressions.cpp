// What the fuzzers found, pinned as exact expectations (ctest's fuzz_replay_<target> replays the
// same files, but only shows that nothing crashes), and the hgt fuzz entry point's promise that
// decodeHgtGrid is the loader's own decoder.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "error.h"
#include "terrain/heightfield.h"

namespace {

std::vector<unsigned char> readRegression(const std::string& name) {
  std::ifstream in(std::string(LODBENCH_SOURCE_DIR) + "/tests/fuzz/regressions/" + name, std::ios::binary);
  EXPECT_TRUE(in.good()) << name;
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string decodeError(const lb::TerrainSpec& spec, const std::vector<unsigned char>& bytes) {
  try {
    lb::decodeHeightfield(spec, bytes);
  } catch (const lb::InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

lb::TerrainSpec pngSpec(const std::string& file) {
  lb::TerrainSpec s;
  s.type = "png16";
  s.file = file;
  s.heightScale = 1.0f;
  return s;
}

}  // namespace

// stb_image allocates what an IDAT chunk's length claims before reading it: a 72-byte file took
// 30 s (timeout) and a 112-byte one asked for 2 GiB (out of memory) in the long fuzz runs.
TEST(FuzzRegressions, PngChunkPastTheEndIsRefusedBeforeDecoding) {
  for (const char* name :
       {"png16/idat-chunk-claims-1.3gb-past-the-end.png", "png16/idat-chunk-claims-1.2gb-past-the-end.png"}) {
    const std::string msg = decodeError(pngSpec(name), readRegression(name));
    EXPECT_NE(msg.find(name), std::string::npos) << msg;
    EXPECT_NE(msg.find("past the end of the file"), std::string::npos) << msg;
  }
}

// A 100-byte file whose header claims 16385^2 samples took 3.5 s under ASan to fail in the decoder.
TEST(FuzzRegressions, PngHeaderLargerThanItsCompressedDataIsRefused) {
  const char* name = "png16/header-claims-16385x16385-with-tiny-idat.png";
  const std::string msg = decodeError(pngSpec(name), readRegression(name));
  EXPECT_NE(msg.find("16385x16385"), std::string::npos) << msg;
  EXPECT_NE(msg.find("cannot hold"), std::string::npos) << msg;
}

// The hgt fuzz target decodes small grids with decodeHgtGrid; at 1201 it must be the loader.
TEST(FuzzRegressions, HgtGridDecoderIsTheLoadersDecoder) {
  lb::TerrainSpec s;
  s.type = "hgt";
  s.file = "grid.hgt";
  s.heightScale = 2.0f;
  const int n = 1201;
  std::vector<unsigned char> bytes(size_t(n) * n * 2);
  for (size_t i = 0; i < bytes.size() / 2; ++i) {
    const int16_t v = (i % 97 == 0) ? int16_t(-32768) : int16_t(int(i % 3001) - 500);  // voids among valid samples
    bytes[2 * i] = uint8_t(uint16_t(v) >> 8);
    bytes[2 * i + 1] = uint8_t(uint16_t(v) & 0xff);
  }
  const lb::Heightfield a = lb::decodeHeightfield(s, bytes), b = lb::decodeHgtGrid(s, bytes, n);
  EXPECT_EQ(a.width, n);
  EXPECT_EQ(b.width, n);
  EXPECT_TRUE(a.h == b.h);
  EXPECT_EQ(a.minHeight, b.minHeight);
  EXPECT_EQ(a.maxHeight, b.maxHeight);

  // Small grids: voids filled from their neighbours, a wrong length named, all-void refused.
  const std::vector<unsigned char> small = {0x00, 0x0a, 0x80, 0x00, 0x80, 0x00, 0x00, 0x14};  // 10, void, void, 20
  const lb::Heightfield g = lb::decodeHgtGrid(s, small, 2);
  EXPECT_EQ(std::vector<float>(g.h.begin(), g.h.end()), (std::vector<float>{20.0f, 30.0f, 30.0f, 40.0f}));
  EXPECT_THROW(lb::decodeHgtGrid(s, small, 3), lb::InputError);
  EXPECT_THROW(lb::decodeHgtGrid(s, {0x80, 0x00, 0x80, 0x00, 0x80, 0x00, 0x80, 0x00}, 2), lb::InputError);
}

// stb_image probed the JPEG decoder on a non-PNG input and its Huffman table builder wrote past
// its array (UBSan, png16 long run): only PNG is compiled in, and a file without the PNG
// signature is refused before any decoder runs.
TEST(FuzzRegressions, NonPngIsRefusedBeforeAnyDecoder) {
  const char* name = "png16/jpeg-huffman-table-overflow-in-stb.bin";
  const std::string msg = decodeError(pngSpec(name), readRegression(name));
  EXPECT_NE(msg.find("cannot decode PNG (no PNG signature)"), std::string::npos) << msg;
}
