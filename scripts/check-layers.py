#!/usr/bin/env python3
"""Fails when a source file includes a project header its folder may not include.

The rules are the layer table of docs/architecture.md (section "Layers"): one row per folder,
its first cell the folder in backticks, its last cell the folders it may include, each in
backticks (or "nothing"). A folder may always include itself and the loose headers at the top of
harness/ (error.h, number_text.h). Tests, benchmarks and fuzz targets may include anything.
Usage: scripts/check-layers.py [repo-root]   Exit 0 when clean, 1 with one line per violation.
"""
import re
import sys
from pathlib import Path

root = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent)
doc = root / "docs" / "architecture.md"


def read_table():
    text = doc.read_text(encoding="utf-8")
    m = re.search(r"^## Layers\s*$(.*?)(?=^## )", text, re.M | re.S)
    if not m:
        sys.exit(f"{doc}: no '## Layers' section")
    rules = {}
    for line in m.group(1).splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) < 2 or not cells[0].startswith("`"):
            continue
        folder = cells[0].strip("`").rstrip("/")
        allowed = {a.rstrip("/") for a in re.findall(r"`([^`]+)`", cells[-1])}
        rules[folder] = allowed
    if not rules:
        sys.exit(f"{doc}: the Layers table has no rows")
    return rules


def folder_of_include(inc, rules):
    """The deepest table folder a quoted include names, or None for a loose or relative header."""
    best = None
    for path in (inc, "harness/" + inc):
        for r in rules:
            if r == "harness":  # its loose headers may be included from anywhere
                continue
            if path.startswith(r + "/") and (best is None or len(r) > len(best)):
                best = r
    return best


def main():
    rules = read_table()
    bad = []
    for folder in sorted(rules):
        base = root / folder
        if not base.is_dir():
            bad.append(f"docs/architecture.md: folder {folder} in the Layers table does not exist")
            continue
        for f in sorted(base.rglob("*")):
            if f.suffix not in (".h", ".cpp", ".glsl", ".comp", ".vert", ".frag", ".tesc", ".tese", ".geom"):
                continue
            # The deepest table folder holding the file owns it (harness/ holds harness/vk/ ...).
            owner = max((r for r in rules if (root / r) in f.parents), key=len)
            if owner != folder:
                continue
            for n, line in enumerate(f.read_text(encoding="utf-8", errors="replace").splitlines(), 1):
                m = re.match(r'\s*#\s*include\s+"([^"]+)"', line)
                if not m:
                    continue
                target = folder_of_include(m.group(1), rules)
                if target is None:
                    # A path relative to the including file (a sibling header) stays in its folder.
                    if (f.parent / m.group(1)).exists() or (root / "harness" / m.group(1)).exists():
                        continue
                    bad.append(f"{f.relative_to(root)}:{n}: includes \"{m.group(1)}\", which is in no folder of the Layers table")
                    continue
                if target != owner and target not in rules[owner]:
                    bad.append(f"{f.relative_to(root)}:{n}: {owner} may not include {target} (\"{m.group(1)}\"); "
                               f"allowed: {', '.join(sorted(rules[owner])) or 'nothing'}")
    for b in bad:
        print(b)
    if bad:
        print(f"check-layers: {len(bad)} include(s) against docs/architecture.md's Layers table", file=sys.stderr)
        return 1
    print(f"check-layers: {len(rules)} folders, every include within the Layers table")
    return 0


if __name__ == "__main__":
    sys.exit(main())
