#!/usr/bin/env bash
# Installs the Debian packages lodbench needs, only those that are missing.
set -euo pipefail
pkgs=(build-essential cmake pkg-config git
      libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools glslang-dev spirv-tools
      libglm-dev nlohmann-json3-dev libmeshoptimizer-dev libfccp-dev libbenchmark-dev libgtest-dev libstb-dev libcli11-dev
      zlib1g-dev  # PNG compression of run images
      libgdal-dev  # terrain type gdal (any raster DEM); off in LODBENCH_STATIC_RUNTIME builds
      clang-format  # scripts/check-code.sh: formatting is checked in CI
      libbenchmark-tools python3-scipy)  # the last two: a test feeds our gbench.json to Google Benchmark's compare.py
bash "$(dirname "$0")/apt-install.sh" "${pkgs[@]}"
