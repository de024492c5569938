#!/usr/bin/env bash
# Sets up the report renderer (report/render.mjs) and its browser test: Node.js, npm and Debian's
# chromium from apt where missing, then the locked npm packages (vega, vega-lite, vega-embed,
# playwright-core) into report/node_modules. No browser is downloaded: the test drives
# /usr/bin/chromium. The harness itself needs none of this.
set -euo pipefail
cd "$(dirname "$0")/.."
# Only what is missing: a node or chromium that is already on PATH (from elsewhere) is used as is.
pkgs=()
command -v node >/dev/null || pkgs+=(nodejs)
command -v npm >/dev/null || pkgs+=(npm)
command -v chromium >/dev/null || command -v chromium-browser >/dev/null || pkgs+=(chromium)
((${#pkgs[@]} == 0)) || bash scripts/apt-install.sh "${pkgs[@]}"
major=$(node -p 'process.versions.node.split(".")[0]')
if ((major < 18)); then
  echo "lodbench: report/ needs Node.js 18 or newer, found $(node --version)" >&2
  exit 1
fi
# npm ci deletes and reinstalls node_modules every time: skip it while the installed packages are
# the ones this package-lock.json names (its digest is kept beside them).
lock_sum=$(sha256sum report/package-lock.json | cut -d' ' -f1)
stamp=report/node_modules/.lodbench-lock.sha256
if [[ -f $stamp && $(cat "$stamp") == "$lock_sum" ]]; then
  echo "lodbench: report renderer ready (report/node_modules matches package-lock.json)" >&2
else
  (cd report && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund)
  echo "$lock_sum" >"$stamp"
  echo "lodbench: report renderer ready" >&2
fi
# The browser test joins ctest at the next cmake run. scripts/test.sh and scripts/run-default.sh run
# cmake right after this (--cmake-follows), so only a build configured earlier by hand needs the hint.
if [[ ${1:-} != --cmake-follows && -f build/CTestTestfile.cmake ]] && ! grep -q report_browser build/CTestTestfile.cmake; then
  echo "lodbench: re-run cmake (bash scripts/build.sh -DLODBENCH_TESTS=ON) to add the report_browser test to build/" >&2
fi
