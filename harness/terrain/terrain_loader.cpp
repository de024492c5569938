// Heightfield files: SRTM .hgt, 16-bit grayscale PNG, raw little-endian R16 / R32F.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "error.h"
#include "terrain/gdal_loader.h"
#include "terrain/heightfield.h"
#include "terrain/parallel_rows.h"
#include "terrain/void_fill.h"

// The one stb_image implementation in the project (image_io.cpp owns stb_image_write's).
// PNG only (the heightmaps here and the ray-cast cache's images): stb_image probes every format
// it knows on any input, and its JPEG Huffman table builder writes past its array on a 72-byte
// input (UBSan, found by the png16 fuzzer; tests/fuzz/regressions/png16).
#define STBI_ONLY_PNG
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

namespace lb {
namespace {

constexpr int16_t kHgtVoid = -32768;
constexpr int kMaxPngSide = 16385;

std::vector<unsigned char> readFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": is a directory, not a heightmap file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot open " + path);
  // One read of the known size: a 1 GiB raw terrain took 4.6 s through a stream iterator.
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0, std::ios::beg);
  if (size < 0 || !in) throw InputError(path + ": cannot tell the file's size");
  std::vector<unsigned char> bytes(static_cast<size_t>(size));
  in.read(reinterpret_cast<char*>(bytes.data()), size);
  if (in.gcount() != size) throw InputError(path + ": read error");
  return bytes;
}

Heightfield emptyField(const TerrainSpec& spec, int w, int h) {
  Heightfield hf;
  hf.width = w;
  hf.height = h;
  hf.extent = spec.extent;
  hf.h.resize(size_t(w) * size_t(h));
  return hf;
}

// SRTM: no header; N x N big-endian int16 metres, first row = north edge, first column = west.
// Orientation in lodbench: file row r becomes z = r and column c becomes x = c, so +x points east
// and +z points south (north is at z = 0).
Heightfield decodeHgtSamples(const TerrainSpec& spec, const std::vector<unsigned char>& bytes, int n) {
  Heightfield hf = emptyField(spec, n, n);
  std::vector<char> known(hf.h.size(), 1);
  bool anyVoid = false, anyValid = false;
  for (size_t i = 0; i < hf.h.size(); ++i) {
    const int16_t m = int16_t(uint16_t(bytes[2 * i] << 8 | bytes[2 * i + 1]));
    if (m == kHgtVoid) {
      known[i] = 0;
      anyVoid = true;
      ++hf.source.nodataCount;
    } else {
      hf.h[i] = float(m) * spec.heightScale;
      anyValid = true;
    }
  }
  if (!anyValid) throw InputError(spec.file + ": every sample is a void (-32768)");
  // With at least one valid sample the breadth-first fill reaches every void, so no void is
  // ever isolated and the "minimum valid height" fallback is never needed.
  if (anyVoid) fillVoids(hf.h, known, n, n);
  return hf;
}

// SRTM tiles are 1201^2 (3") or 3601^2 (1"), but a crop of one (tests/data) keeps the format at
// another side, so any square grid of int16 samples is accepted; the side follows from the size.
Heightfield loadHgt(const TerrainSpec& spec, const std::vector<unsigned char>& bytes) {
  const size_t samples = bytes.size() / 2;
  size_t n = size_t(std::llround(std::sqrt(double(samples))));
  while (n * n > samples) --n;
  while ((n + 1) * (n + 1) <= samples) ++n;
  if (bytes.size() % 2 != 0 || n * n != samples || n < 2 || n > size_t(kMaxPngSide))
    throw InputError(spec.file + ": size " + std::to_string(bytes.size()) +
                     " bytes is not N^2 int16 samples with 2 <= N <= " + std::to_string(kMaxPngSide) +
                     " (SRTM tiles are 1201^2 or 3601^2)");
  return decodeHgtSamples(spec, bytes, int(n));
}

// stb_image memcpy()s from a null pointer on a zero-length IDAT chunk (undefined behaviour that
// UBSan reports; found by fuzzing, tests/fuzz/regressions/png16). Such a chunk is legal but no
// encoder writes one, so refuse the file rather than hand it to the decoder.
// Returns the total length of the IDAT chunks (the compressed image).
size_t rejectEmptyIdat(const TerrainSpec& spec, const std::vector<unsigned char>& bytes) {
  auto be32 = [&](size_t at) {
    return uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 | uint32_t(bytes[at + 2]) << 8 |
           uint32_t(bytes[at + 3]);
  };
  size_t idat = 0;
  if (bytes.size() < 8 || std::memcmp(bytes.data(), "\x89PNG\r\n\x1a\n", 8) != 0)
    throw InputError(spec.file + ": cannot decode PNG (no PNG signature)");
  for (size_t at = 8; at + 8 <= bytes.size();) {  // after the 8-byte signature: length, type, data, crc
    const uint32_t len = be32(at);
    const bool isIdat = std::memcmp(&bytes[at + 4], "IDAT", 4) == 0;
    if (len == 0 && isIdat)
      throw InputError(spec.file + ": PNG has an empty IDAT chunk at byte " + std::to_string(at) + " (not supported)");
    // The decoder would first allocate what a truncated chunk claims (a 72-byte file claiming a
    // 1.3 GB IDAT timed out the fuzzer), so a chunk running past the end is refused here.
    if (size_t(len) > bytes.size() - at - 8)
      throw InputError(spec.file + ": PNG chunk at byte " + std::to_string(at) + " claims " + std::to_string(len) +
                       " bytes, past the end of the file (" + std::to_string(bytes.size()) + " bytes)");
    if (isIdat) idat += len;
    if (std::memcmp(&bytes[at + 4], "IEND", 4) == 0) break;  // the decoder ignores what follows
    at += 12 + size_t(len);
  }
  return idat;
}

// Deflate expands at most 1032:1 (a 258-byte match in 2 bits). A header asking for more image
// data than its IDAT chunks can hold is refused before the decoder allocates for it: a 100-byte
// file claiming 16385^2 samples took 3.5 s under ASan to fail (found by fuzzing).
void rejectImpossibleSize(const TerrainSpec& spec, size_t idat, int w, int h) {
  const double raw = 2.0 * double(w) * double(h);  // 16-bit samples, less than the filtered stream
  if (raw > 1032.0 * double(idat))
    throw InputError(spec.file + ": PNG header says " + std::to_string(w) + "x" + std::to_string(h) +
                     " but its compressed data (" + std::to_string(idat) + " bytes) cannot hold that many samples");
}

Heightfield loadPng16(const TerrainSpec& spec, const std::vector<unsigned char>& bytes) {
  const size_t idat = rejectEmptyIdat(spec, bytes);
  if (bytes.size() > size_t(INT32_MAX)) throw InputError(spec.file + ": file too large for a PNG heightmap");
  const int len = int(bytes.size());
  int w = 0, h = 0, comp = 0;
  if (!stbi_info_from_memory(bytes.data(), len, &w, &h, &comp))
    throw InputError(spec.file + ": cannot decode PNG (" + std::string(stbi_failure_reason()) + ")");
  if (!stbi_is_16_bit_from_memory(bytes.data(), len) || comp != 1)
    throw InputError(spec.file + ": not a 16-bit grayscale PNG (found " + std::to_string(comp) + " channel(s), " +
                     (stbi_is_16_bit_from_memory(bytes.data(), len) ? "16" : "8") + "-bit)");
  if (w < 2 || h < 2)
    throw InputError(spec.file + ": " + std::to_string(w) + "x" + std::to_string(h) + " is too small (need 2x2)");
  // The largest procedural size too; also keeps a forged header from asking for gigabytes.
  if (w > kMaxPngSide || h > kMaxPngSide)
    throw InputError(spec.file + ": " + std::to_string(w) + "x" + std::to_string(h) + " is larger than " +
                     std::to_string(kMaxPngSide) + " samples per side");
  rejectImpossibleSize(spec, idat, w, h);
  stbi_us* pixels = stbi_load_16_from_memory(bytes.data(), len, &w, &h, &comp, 1);
  if (!pixels) throw InputError(spec.file + ": cannot decode PNG (" + std::string(stbi_failure_reason()) + ")");
  Heightfield hf = emptyField(spec, w, h);
  // Stored value x heightScale, like r16 and hgt: a 16-bit DEM stores metres (or decimetres with 0.1).
  for (size_t i = 0; i < hf.h.size(); ++i) hf.h[i] = float(pixels[i]) * spec.heightScale;
  stbi_image_free(pixels);
  return hf;
}

// Raw dumps carry no header, so the user supplies the size and it must match the file exactly.
Heightfield loadRaw(const TerrainSpec& spec, const std::vector<unsigned char>& bytes, size_t bytesPerSample) {
  if (spec.rawWidth < 2 || spec.rawHeight < 2)
    throw InputError(spec.file + ": " + spec.type +
                     " needs a width and height of at least 2 samples (config: terrain " +
                     "'width' and 'height'; render: --terrain-width and --terrain-height), got " +
                     std::to_string(spec.rawWidth) + "x" + std::to_string(spec.rawHeight));
  const size_t expected = size_t(spec.rawWidth) * size_t(spec.rawHeight) * bytesPerSample;
  if (bytes.size() != expected)
    throw InputError(spec.file + ": expected " + std::to_string(spec.rawWidth) + "*" + std::to_string(spec.rawHeight) +
                     "*" + std::to_string(bytesPerSample) + " = " + std::to_string(expected) + " bytes, got " +
                     std::to_string(bytes.size()));
  Heightfield hf = emptyField(spec, spec.rawWidth, spec.rawHeight);
  // Row bands in parallel; a band stops at its first non-finite sample and parallelRows rethrows
  // the lowest band's error, so the message names the file's first one whatever the thread count.
  const size_t w = size_t(spec.rawWidth);
  parallelRows(spec.rawHeight, [&](int r0, int r1) {
    for (size_t i = size_t(r0) * w; i < size_t(r1) * w; ++i) {
      const unsigned char* p = &bytes[i * bytesPerSample];
      if (bytesPerSample == 2) {
        hf.h[i] = float(uint16_t(p[0] | p[1] << 8)) * spec.heightScale;
      } else {
        const uint32_t u = uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
        float v;
        std::memcpy(&v, &u, sizeof v);
        if (!std::isfinite(v))
          throw InputError(spec.file + ": sample (" + std::to_string(i % size_t(spec.rawWidth)) + ", " +
                           std::to_string(i / size_t(spec.rawWidth)) + ") is not a finite number");
        hf.h[i] = v * spec.heightScale;
      }
    }
  });
  return hf;
}

// Non-finite samples are caught per type above; this bounds the product with heightScale.
void checkHeights(const TerrainSpec& spec, const Heightfield& hf) {
  for (size_t i = 0; i < hf.h.size(); ++i)
    if (!(std::fabs(hf.h[i]) <= kMaxAbsHeight))
      throw InputError(spec.file + ": sample (" + std::to_string(i % size_t(hf.width)) + ", " +
                       std::to_string(i / size_t(hf.width)) + ") is " + std::to_string(hf.h[i]) +
                       " after height_scale; heights must lie within +-1e5 (float32 precision, and 5x Earth's relief "
                       "of -11 km to +8.8 km in metres): check the file type and height_scale");
}

// The case file's "terrain.source" for the built-in readers: no CRS, one band, the config's extent.
void describeSource(const TerrainSpec& spec, Heightfield& hf) {
  TerrainSource& s = hf.source;
  s.driver = spec.type;
  s.rasterWidth = hf.width;
  s.rasterHeight = hf.height;
  s.dataType = spec.type == "hgt" ? "Int16" : spec.type == "r32f" ? "Float32" : "UInt16";
  s.extent = hf.extent;
  s.extentSource = "config";
}

}  // namespace

Heightfield loadHeightfield(const TerrainSpec& spec) {
  if (spec.file.empty()) throw InputError("terrain: type '" + spec.type + "' needs a file");
  if (spec.type == "gdal") {
    Heightfield hf = loadGdal(spec);
    checkHeights(spec, hf);
    hf.updateRange();
    return hf;
  }
  return decodeHeightfield(spec, readFile(spec.file));
}

Heightfield decodeHeightfield(const TerrainSpec& spec, const std::vector<unsigned char>& bytes) {
  if (!(std::isfinite(spec.extent) && spec.extent > 0.0f))
    throw InputError(spec.file + ": terrain extent " + std::to_string(spec.extent) + " must be positive and finite");
  if (!(std::isfinite(spec.heightScale) && spec.heightScale >= 0.0f))
    throw InputError(spec.file + ": terrain heightScale " + std::to_string(spec.heightScale) +
                     " must be finite and >= 0");
  Heightfield hf;
  if (spec.type == "hgt")
    hf = loadHgt(spec, bytes);
  else if (spec.type == "png16")
    hf = loadPng16(spec, bytes);
  else if (spec.type == "r16")
    hf = loadRaw(spec, bytes, 2);
  else if (spec.type == "r32f")
    hf = loadRaw(spec, bytes, 4);
  else if (spec.type == "gdal")  // GDAL reads files, not byte buffers
    throw InputError(spec.file + ": type 'gdal' is read through loadHeightfield, from the file");
  else
    throw InputError(spec.file + ": '" + spec.type +
                     "' is not a terrain file type (valid: hgt, png16, r16, r32f, gdal)");
  checkHeights(spec, hf);
  describeSource(spec, hf);
  hf.updateRange();
  return hf;
}

Heightfield decodeHgtGrid(const TerrainSpec& spec, const std::vector<unsigned char>& bytes, int side) {
  if (side < 2 || bytes.size() != size_t(side) * size_t(side) * 2)
    throw InputError(spec.file + ": " + std::to_string(bytes.size()) + " bytes is not " + std::to_string(side) +
                     "^2 int16 samples");
  Heightfield hf = decodeHgtSamples(spec, bytes, side);
  checkHeights(spec, hf);
  hf.updateRange();
  return hf;
}

}  // namespace lb
