#!/usr/bin/env bash
# The habits that keep the code readable, checked before anything is built: every include within
# the layer table of docs/architecture.md, and every C++ file formatted as .clang-format says
# (clang-format 14, Debian 12's; another version formats some constructs differently).
# Fix formatting with: git ls-files '*.cpp' '*.h' | xargs clang-format -i
set -euo pipefail
cd "$(dirname "$0")/.."
python3 scripts/check-layers.py
mapfile -t files < <(git ls-files '*.cpp' '*.h')
if ! clang-format --dry-run -Werror "${files[@]}" 2>/tmp/lodbench-format.$$; then
  grep -E '^[^ ].*(warning|error):' /tmp/lodbench-format.$$ | cut -d: -f1 | sort -u | sed 's/^/not formatted: /' | head -50
  rm -f /tmp/lodbench-format.$$
  echo "check-code: files differ from clang-format; run: git ls-files '*.cpp' '*.h' | xargs clang-format -i" >&2
  exit 1
fi
rm -f /tmp/lodbench-format.$$
echo "check-code: ${#files[@]} C++ files formatted as .clang-format says"
