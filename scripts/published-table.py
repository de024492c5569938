#!/usr/bin/env python3
"""Markdown tables of a published run (summary.json [+ frames.csv.gz]): speed vs accuracy per case,
errbound's promise per measured frame, calibration. Usage: scripts/published-table.py RUN_DIR..."""
import csv, gzip, json, sys, os

def g(s, k, stat='median'):
    v = s.get(k)
    if isinstance(v, dict): v = v.get(stat)
    return v

def fmt(v, nd=3):
    if v is None: return 'null'
    if isinstance(v, float): return f'{v:.{nd}f}'
    return str(v)

for run in sys.argv[1:]:
    s = json.load(open(os.path.join(run, 'summary.json')))
    print(f'\n### {os.path.basename(run.rstrip("/"))}: {len(s["cases"])} cases\n')
    print('| case | GPU ms median | GPU ms p95 | triangles median | err mean px | err p95 px | err max px | PSNR dB vs ray cast | surplus | cracks (analytic/pixels) | calib. drift |')
    print('|---|---|---|---|---|---|---|---|---|---|---|')
    for c in sorted(s['cases'], key=lambda c: (c['path'], c['scheme'], c['case_id'])):
        m = c['summary']
        cal = m.get('calibration') or {}
        drift = cal.get('drift')
        print('| {} | {} | {} | {:,} | {} | {} | {} | {} | {} | {}/{} | {}{} |'.format(
            c['case_id'], fmt(g(m, 'gpu_ms')), fmt(g(m, 'gpu_ms', 'p95')), int(g(m, 'triangles') or 0),
            fmt(g(m, 'err_mean_px', 'mean')), fmt(g(m, 'err_p95_px', 'mean')), fmt(g(m, 'err_max_px', 'max')),
            fmt(g(m, 'img_psnr_db', 'mean'), 1), fmt(g(m, 'surplus', 'mean'), 2),
            fmt(g(m, 'cracks_analytic', 'max'), 0), fmt(g(m, 'cracks_pixels', 'max'), 0),
            'null' if drift is None else f'{100*drift:+.2f}%', ' FLAGGED' if cal.get('flagged') else ''))
    path = os.path.join(run, 'frames.csv.gz')
    if os.path.exists(path):
        rows = list(csv.DictReader(io.TextIOWrapper(gzip.open(path), 'utf-8'))) if False else list(csv.DictReader(gzip.open(path, 'rt')))
        worst = {}
        for r in rows:
            cid = r['case_id']
            if not cid.startswith('errbound') or r.get('err_max_px', '') in ('', 'null'): continue
            bound = float(cid.split('max_error_px')[1].split('_')[0]) if 'max_error_px' in cid else 1.0
            unmet = float(r.get('errbound_unmet_patches') or 0)
            w = worst.setdefault(cid, [None, 0, 0, 0.0])
            w[2] += 1
            ratio = float(r['err_max_px']) / bound
            w[3] = max(w[3], ratio)
            if unmet > 0: w[1] += 1
            else: w[0] = ratio if w[0] is None else max(w[0], ratio)
        if worst:
            print('\nerrbound: worst measured err_max_px / max_error_px over measured frames whose bound could be met;'
                  ' frames with unmet patches counted apart\n')
            print('| case | measured frames | frames with unmet patches | worst err_max / bound (met frames) | worst err_max / bound (all frames) |')
            print('|---|---|---|---|---|')
            for cid, (w, un, n, wa) in sorted(worst.items()):
                print(f'| {cid} | {n} | {un} | {"none met" if w is None else f"{w:.3f}"} | {wa:.3f} |')
