#!/usr/bin/env python3
"""Markdown tables of the draw-path runs (configs/gpu-draw-paths.json, configs/gpu-equal-error-*.json):
per case the path, GPU ms (median, p95), the LOD/draw split, the CPU selection, triangles submitted and
non-degenerate (measured frames), error and cracks. Usage: scripts/draw-paths-table.py RUN_DIR... (a run folder, or a published one with cases.tar.gz)"""
import json, os, sys, tarfile

INSTANCED = {"cdlod", "cdlod-sse", "clipmap"}

def stat(s, k, st="median"):
    v = s.get(k)
    return v.get(st) if isinstance(v, dict) else v

def f(v, nd=3):
    if v is None: return "null"
    if isinstance(v, float): return f"{v:.{nd}f}"
    return str(v)

for run in sys.argv[1:]:
    cases = []
    if os.path.isdir(os.path.join(run, "cases")):
        for name in sorted(os.listdir(os.path.join(run, "cases"))):
            cases.append(json.load(open(os.path.join(run, "cases", name))))
    else:  # a published folder keeps its case files as cases.tar.gz
        with tarfile.open(os.path.join(run, "cases.tar.gz")) as t:
            for m in sorted(t.getmembers(), key=lambda m: m.name):
                if m.name.endswith(".json"): cases.append(json.load(t.extractfile(m)))
    print(f"\n### {os.path.basename(run.rstrip('/'))}: {len(cases)} cases\n")
    print("| scheme | path | parameter | p95 error px (match) | GPU ms median | GPU ms p95 | LOD GPU ms | draw GPU ms "
          "| LOD CPU ms | triangles (measured frames, mean) | non-degenerate | err mean px | err p95 px | cracks analytic/pixels |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    rows = []
    for c in cases:
        s = c["summary"]
        m = c.get("matched") or {}
        param = f"{m['param']}={m['value']:.4g}" if m.get("param") else ", ".join(f"{k}={v}" for k, v in c["params"].items()) or "defaults"
        ach = f"{m['achieved']:.3f}" + ("" if m.get("reachable", True) else " (unreachable)") if m.get("param") else "-"
        meas = [fr for fr in c["frames"] if isinstance(fr.get("hist"), list)]
        tri = sum(sum(fr["hist"]) + fr["hist_offscreen"] + fr["hist_backfacing"] for fr in meas) / max(1, len(meas))
        deg = sum(fr.get("hist_degenerate", 0) for fr in meas) / max(1, len(meas))
        cr = f"{f(stat(s, 'cracks_analytic', 'max'), 0)}/{f(stat(s, 'cracks_pixels', 'max'), 0)}" if "cracks_analytic" in s else "-"
        rows.append((stat(s, "gpu_ms"), "| " + " | ".join([
            c["scheme"], "instanced" if c["scheme"] in INSTANCED else "tessellation", param, ach,
            f(stat(s, "gpu_ms")), f(stat(s, "gpu_ms", "p95")), f(stat(s, "lod_ms"), 4), f(stat(s, "draw_ms")),
            f(stat(s, "lod_cpu_ms"), 4), f"{tri:,.0f}", f"{tri - deg:,.0f}", f(stat(s, "err_mean_px", "mean")),
            f(stat(s, "err_p95_px", "mean")), cr]) + " |"))
    for _, r in sorted(rows, key=lambda x: x[0] or 0):
        print(r)
