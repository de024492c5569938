#pragma once
// SHA-256 (FIPS 180-4) of bytes and files, for case digests. A self-contained implementation so
// the digest needs no new dependency; tests pin it to the FIPS test vectors. Not for security:
// it names inputs, so equal digests mean equal inputs across machines and versions.
#include <cstdint>
#include <string>

namespace lb {

class Sha256 {
 public:
  Sha256();
  void update(const void* data, size_t size);
  void update(const std::string& s) { update(s.data(), s.size()); }
  std::string hex();  // finishes: 64 lowercase hex digits

 private:
  void block(const uint8_t* p);
  uint32_t h_[8];
  uint8_t buf_[64];
  size_t used_ = 0;
  uint64_t bytes_ = 0;
};

std::string sha256Hex(const std::string& bytes);
// Throws InputError naming the file when it cannot be read.
std::string sha256File(const std::string& file);

}  // namespace lb
