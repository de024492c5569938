#!/usr/bin/env python3
"""Tessellator, instancing and mesh shaders side by side: one Markdown table per run folder of
the mesh twins (sphere integer 1 / sphere-ms, cdlod / cdlod-ms, cbt / cbt-ms, sphere as the
tessellator's default), per view: median GPU, LOD and draw ms, median triangles, p95 error, and
each mesh scheme's GPU time over its twin's with the repetitions' spread of that ratio.

Usage: scripts/mesh-table.py RUN_DIR [RUN_DIR...]   (a merged run folder: summary.json)
"""
import json
import os
import statistics
import sys

PAIRS = [("sphere-integer1", "sphere-ms"), ("cdlod", "cdlod-ms"), ("cbt", "cbt-ms")]


def view_of(case):
    # The camera path's file name: terrain labels may hold underscores, so not the case id.
    return os.path.splitext(os.path.basename(case["path"]))[0]


def label(case):
    cid = case["case_id"]
    return cid.split("_")[0]


def med(summary, key):
    v = summary.get(key)
    if isinstance(v, dict) and v.get("median") is not None:
        return v["median"]
    return None


def fmt(v, digits=3):
    return "null" if v is None else f"{v:.{digits}f}"


def table(run):
    cases = json.load(open(f"{run}/summary.json"))["cases"]
    by = {}
    views = []
    for c in cases:
        v = view_of(c)
        if v not in views:
            views.append(v)
        by[(label(c), v)] = c
    out = [f"### {run}", ""]
    out.append("| view | scheme | status | GPU ms | LOD ms | draw ms | triangles | p95 px | mesh / twin GPU ms |")
    out.append("|---|---|---|---:|---:|---:|---:|---:|---:|")
    for v in views:
        for name in ["sphere"] + [s for p in PAIRS for s in p]:
            c = by.get((name, v))
            if c is None:
                continue
            s = c.get("summary", {})
            if c["status"] != "ok":
                out.append(f"| {v} | {name} | {c['status']}: {c.get('reason', '')[:80]} | | | | | | |")
                continue
            ratio = ""
            twin = next((a for a, b in PAIRS if b == name), None)
            if twin and by.get((twin, v), {}).get("status") == "ok":
                t = med(by[(twin, v)]["summary"], "gpu_ms")
                ratio = f"{med(s, 'gpu_ms') / t:.3f}"
            tri = med(s, "triangles")
            out.append(
                f"| {v} | {name} | ok | {fmt(med(s, 'gpu_ms'))} | {fmt(med(s, 'lod_ms'))} | {fmt(med(s, 'draw_ms'))} | "
                f"{'null' if tri is None else int(tri)} | {fmt(med(s, 'err_p95_px'), 2)} | {ratio} |")
    # Geometric mean of each pair's ratio over the views where both ran.
    out.append("")
    for twin, mesh in PAIRS:
        r = []
        for v in views:
            a, b = by.get((twin, v)), by.get((mesh, v))
            if a and b and a["status"] == b["status"] == "ok":
                r.append(med(b["summary"], "gpu_ms") / med(a["summary"], "gpu_ms"))
        if r:
            out.append(f"- {mesh} / {twin}: geometric mean {statistics.geometric_mean(r):.3f} over {len(r)} views "
                       f"(min {min(r):.3f}, max {max(r):.3f})")
    return "\n".join(out)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    print("\n\n".join(table(r) for r in sys.argv[1:]))
