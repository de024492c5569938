#!/usr/bin/env python3
"""Markdown tables of a suite's verdict.json (`lodbench verdict`): per workload the verdict, the
cheapest scheme's ms and every scheme's cost over the cheapest's; then per scheme the geometric-mean
ratio with its interval, wins, ties and missing workloads.

Usage: scripts/suite-table.py VERDICT_JSON [--schemes a,b,...]
Marks: `*` the scheme's coarsest configuration is already more accurate than the target (its cost is
an upper bound; it ties the cheapest); `~` the 95 % interval spans more than 10 % of the ratio;
`unreachable` no configuration reached the target (verdict.json names the closest).
"""
import argparse, json, re


def short(workload):
    # proc16385s1-detail_ground_1920x1080 -> proc16385_ground; N44W072_crop601_... -> tile_...
    w = re.sub(r'_\d+x\d+$', '', workload)
    w = re.sub(r'^N44W072_crop601', 'tile', w)
    return re.sub(r's\d+-detail', '', w)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('verdict')
    ap.add_argument('--schemes', help='column order (default: verdict.json\'s scheme order)')
    a = ap.parse_args()
    v = json.load(open(a.verdict))
    schemes = a.schemes.split(',') if a.schemes else [s['scheme'] for s in v['schemes']]
    print('| workload | verdict | cheapest ms | ' + ' | '.join(schemes) + ' |')
    print('|---|---|---:|' + '---:|' * len(schemes))
    for w in sorted(v['workloads'], key=lambda w: short(w['id'])):
        cells = []
        for s in schemes:
            r = w['ratio'].get(s)
            if s in w['missing']:
                cells.append('unreachable' if 'reach' in str(w['missing'][s]) else 'missing')
            elif r is None:
                cells.append('not run')
            else:
                mark = '*' if s in w['notes'] and 'upper bound' in w['notes'][s] else ''
                lo, hi = r.get('lo'), r.get('hi')
                if lo is not None and hi is not None and hi - lo > 0.1 * r['value']:
                    mark += '~'
                cells.append(f"{r['value']:.3f}{mark}")
        verdict = w['cheapest'] if len(w['tied']) <= 1 else 'tie: ' + ', '.join(sorted(w['tied']))
        if len(w['tied']) == len(schemes):
            verdict = f'tie: all {len(schemes)}'
        cheapest = w['cost_ms'].get(w['cheapest'])
        print(f"| {short(w['id'])} | {verdict} | {cheapest:.3f} | " + ' | '.join(cells) + ' |')
    print('\n| scheme | geometric-mean ratio [95 % interval] | workloads | wins | ties | missing |')
    print('|---|---|---:|---:|---:|---:|')
    for s in sorted(v['schemes'], key=lambda s: s['geomean_ratio']['value']):
        g = s['geomean_ratio']
        print(f"| {s['scheme']} | {g['value']:.3f} [{g['lo']:.3f}, {g['hi']:.3f}] | {s['workloads']} | {s['wins']} | "
              f"{s['ties']} | {len(s['missing_in'])} |")


if __name__ == '__main__':
    main()
