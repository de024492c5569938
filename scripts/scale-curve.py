#!/usr/bin/env python3
"""The scale curve: each scheme's cost against the terrain's samples, from one or more runs of the
same views over procedural terrains of several sizes (the workload suite's, and a run of its views
at a larger size). For each view: a Markdown table of GPU ms (median), triangles (median), p95
error, device bytes and host peak per scheme and terrain size, then the cheapest scheme's time at
the smallest and largest size with the growth between them.

Usage: scripts/scale-curve.py [--views ground,flyover] [--target PX] [--controls A,B] RUN...
  RUN  a run folder (its summary.json or summary.json.gz) or such a file; cases of the same scheme,
       view and terrain in several runs: the first run given wins (a warning names the others).
Only procedural terrains take part (labels proc<N>s<seed>...): their spacing and relief ratio are
the same at every size in the suite, so the size is the one variable. A case that failed or missed
its target by over 10 % in its timed frames' measured error (the match bisects on a few frames, so
the timed run's error differs a little from the match's) is marked and left out of "cheapest".
"""
import argparse, gzip, json, os, re, sys


def load(path):
    for name in ('summary.json', 'summary.json.gz'):
        if os.path.isdir(path) and os.path.exists(os.path.join(path, name)):
            path = os.path.join(path, name)
            break
    if os.path.isdir(path):
        sys.exit(f'scale-curve: {path}: no summary.json or summary.json.gz in it')
    opener = gzip.open if path.endswith('.gz') else open
    with opener(path, 'rt') as f:
        return path, json.load(f)


def stat(summary, key, which):
    v = summary.get(key)
    return v.get(which) if isinstance(v, dict) else v


def view_of(case):
    return os.path.splitext(os.path.basename(case['path']))[0]


def size_of(terrain):
    m = re.match(r'proc(\d+)s\d+', terrain)
    return int(m.group(1)) if m else None


def gb(v):
    return 'null' if v is None else f'{v / 1e9:.2f}'


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--views', default='ground,flyover')
    ap.add_argument('--target', type=float, default=1.0, help='the p95 px the runs matched (default 1)')
    ap.add_argument('--controls', default='sphere-copy,sphere-twice',
                    help='schemes shown but never "cheapest" (the suite\'s control schemes)')
    ap.add_argument('runs', nargs='+')
    a = ap.parse_args()
    views = a.views.split(',')
    cells = {}  # (view, scheme, size) -> case
    for run in a.runs:
        path, doc = load(run)
        for c in doc['cases']:
            size = size_of(c['terrain'])
            if size is None or view_of(c) not in views:
                continue
            key = (view_of(c), c['scheme'], size)
            if key in cells:
                print(f'<!-- {key}: kept the first run\'s case, not {path}\'s -->')
                continue
            cells[key] = c
    if not cells:
        sys.exit('scale-curve: no case of a procedural terrain and the views ' + a.views)
    for view in views:
        sizes = sorted({k[2] for k in cells if k[0] == view})
        schemes = sorted({k[1] for k in cells if k[0] == view})
        if not sizes:
            print(f'\n## {view}: no cases\n')
            continue
        print(f'\n## {view}\n')
        print('GPU ms median / triangles median / p95 px / device GB / host peak GB (x raw heights)\n')
        print('| scheme | ' + ' | '.join(f'{s}^2' for s in sizes) + ' |')
        print('|---|' + '---:|' * len(sizes))
        best = {}
        for scheme in schemes:
            row = []
            for s in sizes:
                c = cells.get((view, scheme, s))
                if c is None:
                    row.append('not run')
                    continue
                if c['status'] != 'ok':
                    row.append(f"{c['status']}: {c.get('reason', '')[:60]}")
                    continue
                m = c['summary']
                ms, tri = stat(m, 'gpu_ms', 'median'), stat(m, 'triangles', 'median')
                err = stat(m, 'err_p95_px', 'mean')
                mem = m.get('memory') or {}
                host = mem.get('host_peak_bytes')
                ratio = '' if host is None else f' ({host / (4.0 * s * s):.2f}x)'
                met = err is not None and err <= a.target * 1.1
                row.append(f"{ms:.3f} / {int(tri or 0):,} / {err if err is None else round(err, 2)}"
                           f"{'' if met else ' (over target)'} / {gb(mem.get('gpu_total_bytes'))} / {gb(host)}{ratio}")
                if met and scheme not in a.controls.split(',') and (s not in best or ms < best[s][1]):
                    best[s] = (scheme, ms)
            print(f'| {scheme} | ' + ' | '.join(row) + ' |')
        # The cheapest on target at each size, and its growth over the smallest size's.
        parts = []
        for s in sizes:
            ran = sum(1 for k in cells if k[0] == view and k[2] == s)
            if s not in best:
                parts.append(f'{s}^2: none on target ({ran} of {len(schemes)} schemes ran)')
                continue
            name, ms = best[s]
            growth = f', {100 * (ms / best[sizes[0]][1] - 1):+.1f} %' if sizes[0] in best and s != sizes[0] else ''
            parts.append(f'{s}^2: {name} {ms:.3f} ms{growth}')
        print('\nCheapest on target: ' + '; '.join(parts) + '.')


if __name__ == '__main__':
    main()
