#!/usr/bin/env python3
"""The mesh path's workgroup-shape variants (scripts/mesh-tuning.sh) as one Markdown table: each
mesh scheme's median GPU ms over its twin's, per view, one row per variant folder.

Usage: scripts/mesh-tuning-table.py OUT   (OUT/twins/summary.json and OUT/<variant>/summary.json)
"""
import json
import os
import sys

PAIRS = [("sphere-ms", "sphere"), ("cdlod-ms", "cdlod"), ("cbt-ms", "cbt")]


def medians(path):
    table = {}
    for case in json.load(open(path))["cases"]:
        view = os.path.splitext(os.path.basename(case["path"]))[0]
        gpu = (case["summary"].get("gpu_ms") or {}).get("median")
        table[(case["scheme"], view)] = gpu
    return table


def main():
    out = sys.argv[1]
    twins = medians(os.path.join(out, "twins", "summary.json"))
    views = sorted({v for (_, v) in twins})
    print("| variant | " + " | ".join(f"{ms} / {twin}, {v}" for ms, twin in PAIRS for v in views) + " |")
    print("|---|" + "---:|" * (len(PAIRS) * len(views)))
    for name in sorted(os.listdir(out)):
        path = os.path.join(out, name, "summary.json")
        if name == "twins" or not os.path.isfile(path):
            continue
        ms = medians(path)
        cells = []
        for m, t in PAIRS:
            for v in views:
                a, b = ms.get((m, v)), twins.get((t, v))
                cells.append(f"{a / b:.2f}" if a and b else "null")
        print(f"| {name} | " + " | ".join(cells) + " |")
    print()
    print("| twin | " + " | ".join(views) + " |")
    print("|---|" + "---:|" * len(views))
    for _, t in PAIRS:
        print(f"| {t} ms | " + " | ".join(f"{twins[(t, v)]:.3f}" for v in views) + " |")


if __name__ == "__main__":
    main()
