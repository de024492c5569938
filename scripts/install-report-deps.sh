#!/usr/bin/env bash
# Sets up the report renderer (report/render.mjs) and its browser test: Node.js, npm and Debian's
# chromium from apt where missing, then the locked npm packages (vega, vega-lite, vega-embed,
# playwright-core) into report/node_modules. No browser is downloaded: the test drives
# /usr/bin/chromium. The harness itself needs none of this.
set -euo pipefail
cd "$(dirname "$0")/.."
missing=()
command -v node >/dev/null || missing+=(nodejs)
command -v npm >/dev/null || missing+=(npm)
command -v chromium >/dev/null || command -v chromium-browser >/dev/null || missing+=(chromium)
if ((${#missing[@]})); then
  echo "lodbench: installing ${missing[*]}" >&2
  sudo=""
  [[ $(id -u) -ne 0 ]] && sudo="sudo"
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
major=$(node -p 'process.versions.node.split(".")[0]')
if ((major < 18)); then
  echo "lodbench: report/ needs Node.js 18 or newer, found $(node --version)" >&2
  exit 1
fi
cd report
PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund
echo "lodbench: report renderer ready; re-run cmake to add the report_browser test" >&2
