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
cd report
PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund
echo "lodbench: report renderer ready; re-run cmake to add the report_browser test" >&2
