#!/usr/bin/env python3
"""Compares two runs of configs/cbt-same-tree.json (say lavapipe and a GPU): per case, the converged
tree's SHA-256 and the instance count of every frame. Exit 1 when any case differs.
Usage: scripts/cbt-same-tree.py RUN_A RUN_B"""
import glob, json, os, sys

def cases(run):
    out = {}
    for f in glob.glob(os.path.join(run, "cases", "*.json")):
        c = json.load(open(f))
        out[c["case_id"]] = c
    return out

a, b = cases(sys.argv[1]), cases(sys.argv[2])
bad = 0
for cid in sorted(set(a) | set(b)):
    if cid not in a or cid not in b:
        print(f"{cid}: only in {'A' if cid in a else 'B'}")
        bad += 1
        continue
    sa, sb = a[cid]["summary"], b[cid]["summary"]
    ia = [f.get("instances") for f in a[cid]["frames"]]
    ib = [f.get("instances") for f in b[cid]["frames"]]
    same_tree = sa.get("converged_state_sha256") == sb.get("converged_state_sha256")
    diff = [i for i, (x, y) in enumerate(zip(ia, ib)) if x != y]
    ok = same_tree and not diff and len(ia) == len(ib)
    bad += not ok
    print(f"{cid}: converged tree {'equal' if same_tree else 'DIFFERENT'} "
          f"({sa.get('converged_instances')} / {sb.get('converged_instances')} leaves, "
          f"{sa.get('converge_updates')} / {sb.get('converge_updates')} updates); "
          f"{len(ia) - len(diff)} of {len(ia)} frames with equal instances"
          + (f", first difference at frame {diff[0]}: {ia[diff[0]]} / {ib[diff[0]]}" if diff else ""))
sys.exit(1 if bad else 0)
