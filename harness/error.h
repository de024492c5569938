#pragma once
#include <stdexcept>
#include <string>

namespace lb {
// Bad user input (config, CSV, heightmap, flags). The message names file, line and field.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
// The device lacks a feature a case needs: the case is recorded as skipped, with this reason.
struct FeatureMissing : std::runtime_error {
  using std::runtime_error::runtime_error;
};
}  // namespace lb
