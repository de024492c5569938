#!/usr/bin/env bash
# Installs the Debian packages lodbench needs, only those that are missing.
set -euo pipefail
pkgs=(build-essential cmake pkg-config git
      libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools glslang-dev spirv-tools
      libglm-dev nlohmann-json3-dev libfccp-dev libbenchmark-dev libgtest-dev libstb-dev libcli11-dev
      libbenchmark-tools python3-scipy)  # the last two: a test feeds our gbench.json to Google Benchmark's compare.py
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "lodbench: installing ${missing[*]}" >&2
  sudo=""
  [[ $(id -u) -ne 0 ]] && sudo="sudo"
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
