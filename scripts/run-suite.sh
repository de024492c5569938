#!/usr/bin/env bash
# The workload suite (configs/suite/README.md) in one command: every view over your own DEM, or
# over the suite's terrains, then its verdict and report.
# Usage: scripts/run-suite.sh [DEM] [--config FILE] [--device NAME] [--out DIR] [--extent M]
#                             [--height-scale S] [--keep-terrains] [--largest auto|off|N] [--target PX]
#                             [--dry-run] [--no-report] [-- extra `run` args]
#   DEM              any raster GDAL reads (GeoTIFF, COG, ...; terrain type gdal, the extent from its
#                    georeferencing unless --extent), or an SRTM .hgt (type hgt: 1201^2 and 3601^2
#                    tiles are 108 km, other sizes need --extent). It replaces the suite's terrains
#                    (--keep-terrains: runs beside them). Without a DEM the suite's own terrains run,
#                    the SRTM tile N44W072 in place of its committed crop where the tile is found
#                    ($LODBENCH_SRTM_TILE, .data/N44W072.hgt or ../shared/data/N44W072.hgt).
#   --config         the suite config (default configs/suite/gpu.json; configs/suite/mini.json on lavapipe)
#   --device         Vulkan device, name substring or index (default: the config's)
#   --out            default results/suite/<config name>[-<DEM stem>]; the config written there is
#                    OUT/config.json, the run OUT/run (the same command again resumes it)
#   --height-scale   multiplies the DEM's heights (default 1: metres stay metres)
#   --largest        the suite's largest procedural terrain (the largest "size" in the config): auto
#                    (default) sets it to the largest square terrain the device takes (`lodbench
#                    devices`) at the same spacing and relief; N sets it to N; off keeps the config's.
#                    Generated terrains larger than it are left out (the run would refuse them).
#   --target         the matched target in the config's metric (p95 px in the suite's configs;
#                    default the config's 1): the suite's verdict at 0.5 and 2 px is two more runs,
#                    written to <out>-target<PX> by default
# Env: LODBENCH (binary, default build/lodbench). Needs python3 (writes the config).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
bin=${LODBENCH:-build/lodbench}
dem="" config=configs/suite/gpu.json device="" out="" extent="" heightScale=1 keep=0 largest=auto
dryRun=0 report=1 target=""
extra=()
[[ $# -gt 0 && $1 != -* ]] && { dem=$1; shift; }
while [[ $# -gt 0 ]]; do
  case $1 in
    --config) config=$2; shift 2 ;;
    --device) device=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --extent) extent=$2; shift 2 ;;
    --height-scale) heightScale=$2; shift 2 ;;
    --keep-terrains) keep=1; shift ;;
    --largest) largest=$2; shift 2 ;;
    --target) target=$2; shift 2 ;;
    --dry-run) dryRun=1; shift ;;
    --no-report) report=0; shift ;;
    --) shift; extra=("$@"); break ;;
    -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "run-suite: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
command -v python3 >/dev/null || { echo "run-suite: needs python3 to write the config" >&2; exit 2; }
[[ -x $bin ]] || { echo "run-suite: no lodbench binary at $bin (build first, or set LODBENCH)" >&2; exit 2; }
[[ -f $config ]] || { echo "run-suite: no config $config" >&2; exit 2; }
[[ -z $dem || -f $dem ]] || { echo "run-suite: no DEM file $dem" >&2; exit 2; }
if [[ -z $out ]]; then
  name=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["name"])' "$config")
  [[ -n $dem ]] && name+=-$(basename "${dem%.*}")
  [[ -n $target ]] && name+=-target$target
  out=results/suite/$name
fi
mkdir -p "$out"
devices=""
[[ $largest == auto ]] && devices=$("$bin" devices 2>&1 || true)

python3 - "$config" "$out/config.json" "$root" "$dem" "$extent" "$heightScale" "$keep" "$largest" "$device" \
  "$devices" "$target" <<'EOF'
import json, os, re, sys

config, written, root, dem, extent, height_scale, keep, largest, device, devices, target = sys.argv[1:]
base = os.path.dirname(os.path.abspath(config))
c = json.load(open(config))
terrains = c.pop("terrains", None) or [c.pop("terrain", {"type": "procedural"})]
c.pop("terrain", None)
# Relative names in the config are relative to it: the copy names them absolutely.
absolute = lambda f: f if os.path.isabs(f) else os.path.normpath(os.path.join(base, f))
for t in terrains:
    if "file" in t:
        t["file"] = absolute(t["file"])
c["paths"] = [absolute(p) for p in c.get("paths", []) + ([c.pop("path")] if "path" in c else [])]

def fail(msg):
    print("run-suite: " + msg, file=sys.stderr)
    sys.exit(2)

def dem_terrain(file):
    t = {"file": os.path.abspath(file), "height_scale": float(height_scale)}
    if file.lower().endswith(".hgt"):
        side = int(round((os.path.getsize(file) / 2) ** 0.5))
        t["type"] = "hgt"
        if extent:
            t["extent"] = float(extent)
        elif side in (1201, 3601):
            t["extent"] = 108000  # a 1-degree SRTM tile (3" or 1"), as configs/gpu-dem.json
        else:
            fail(f"{file}: a {side}^2 .hgt is not a whole SRTM tile: give its --extent in metres")
    else:
        t["type"] = "gdal"
        if extent:
            t["extent"] = float(extent)
    return t

crop = "N44W072_crop601.hgt"
if dem:
    mine = dem_terrain(dem)
    terrains = [mine] + [t for t in terrains if not t.get("file", "").endswith(crop)] if keep == "1" else [mine]
    c["name"] = c.get("name", "suite") + "-" + os.path.splitext(os.path.basename(dem))[0]
else:
    tiles = [os.environ.get("LODBENCH_SRTM_TILE", ""), os.path.join(root, ".data/N44W072.hgt"),
             os.path.join(root, "../shared/data/N44W072.hgt")]
    tile = next((f for f in tiles if f and os.path.isfile(f)), None)
    for t in terrains:
        if tile and t.get("file", "").endswith(crop):
            t["file"], t["extent"] = os.path.abspath(tile), 108000
            print(f"run-suite: the SRTM tile {tile} in place of the committed crop")

generated = lambda t: t.get("type", "procedural") in ("procedural", "canyon", "spikes", "cliff", "flat")
if largest != "off" and any(generated(t) for t in terrains):
    if largest == "auto":
        # `lodbench devices`: "[i] name: suitable" then "    largest terrain: N x N samples (...)".
        found, want = [], device or c.get("device", "")
        for m in re.finditer(r"^\[(\d+)\] (.*?): (.*)$(?:\n    .*$)*?\n    largest terrain: (\d+) x", devices, re.M):
            found.append((m.group(1), m.group(2), m.group(3) == "suitable", int(m.group(4))))
        pick = [d for d in found if d[2] and (d[0] == want if want.isdigit() else want.lower() in d[1].lower())]
        if not want:
            pick = [d for d in found if d[2] and "llvmpipe" in d[1].lower()] or [d for d in found if d[2]]
        if not pick:
            fail(f"no suitable device matches '{want}' in `lodbench devices`:\n{devices}"
                 "(or give --largest N, or --largest off)")
        side = pick[0][3]
        print(f"run-suite: {pick[0][1]} takes {side}^2 at most")
    else:
        side = int(largest)
    slot = max((t for t in terrains if generated(t)), key=lambda t: t.get("size", 1024))
    old = slot.get("size", 1024)
    if side != old:  # the same spacing and the same relief for the extent
        factor = (side - 1) / (old - 1)
        slot["size"], slot["extent"] = side, slot.get("extent", 1000) * factor
        slot["height_scale"] = slot.get("height_scale", 120) * factor
    kept, seen = [], set()
    for t in terrains:
        key = json.dumps(t, sort_keys=True)
        if generated(t) and t.get("size", 1024) > side:
            print(f"run-suite: left out {t['type']} {t['size']}^2 (the device takes {side}^2)")
        elif key not in seen:
            kept.append(t)
            seen.add(key)
    terrains = kept
c["terrains"] = terrains
if target:
    if "match" not in c:
        fail(f"--target: {config} has no \"match\" section to set the target of")
    try:
        c["match"]["value"] = float(target)
    except ValueError:
        fail(f"--target '{target}': expected a number (pixels of the config's metric)")
    if c["match"]["value"] <= 0:
        fail(f"--target '{target}': must be above 0")
    c["name"] = c.get("name", "suite") + "-target" + target
c["description"] = c.get("description", "") + f" Written by scripts/run-suite.sh from {config}."
with open(written, "w") as f:
    json.dump(c, f, indent=2)
    f.write("\n")
EOF

args=(run "$out/config.json" --out "$out/run")
[[ -n $device ]] && args+=(--device "$device")
if ((dryRun)); then
  "$bin" "${args[@]}" --dry-run "${extra[@]}"
  exit $?
fi
rc=0
"$bin" "${args[@]}" "${extra[@]}" || { rc=$?; [[ $rc -eq 1 ]] || exit $rc; }  # 1: some case failed
"$bin" verdict "$out/run"
if ((report)); then "$bin" report "$out/run" || rc=1; fi
echo "run-suite: $out/run (verdict.json, report/) from $out/config.json"
exit $rc
