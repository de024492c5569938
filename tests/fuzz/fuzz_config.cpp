// libFuzzer target: the config parser (JSON, duplicate keys, every field's checks, the camera
// paths and heightmaps a config names). Bad input must end in lb::InputError, nothing else.
#include <cstddef>
#include <cstdint>
#include <string>

#include "config/config.h"
#include "error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // The shipped configs' directory, so relative paths in the seeds resolve and reach the CSV parser.
    lb::Config c = lb::parseConfig(text, "fuzz.json", LODBENCH_SOURCE_DIR "/configs");
    (void)lb::expandCases(c);
  } catch (const lb::InputError&) {
  }
  return 0;
}
