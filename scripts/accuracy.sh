#!/usr/bin/env bash
# Accuracy and speed of litamin2-odometry on simulated KITTI drives (docs/accuracy.md).
# Usage: scripts/accuracy.sh [OUT]   (OUT defaults to /tmp/litamin2-accuracy)
# Env: FRAMES (default 1000) frames 0:FRAMES of each sequence; SEQS (default "00 01 05 07 08");
#      SWEEP_SEQ (default 07) sequence for the voxel-size sweep; VOXELS (default "1 2 3 4 5 6");
#      POSES (default /work/shared/data/kitti/poses) folder of KITTI ground-truth NN.txt;
#      KEEP_SCANS=1 keeps the simulated scans (~1.6 MB per frame), otherwise each sequence's
#      scans are deleted once it has been run.
# Uses the already built binaries in ${BUILD_DIR:-<repo>/build}/tools; builds nothing.
# Prints markdown tables; they are also written to OUT/results.md.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin="${BUILD_DIR:-$root/build}/tools"
out=${1:-/tmp/litamin2-accuracy}
frames=${FRAMES:-1000}
seqs=${SEQS:-00 01 05 07 08}
sweep_seq=${SWEEP_SEQ:-07}
voxels=${VOXELS:-1 2 3 4 5 6}
poses=${POSES:-/work/shared/data/kitti/poses}
sim="$bin/sim/litamin2-sim"
odo="$bin/odometry/litamin2-odometry"
for b in "$sim" "$odo"; do
  [ -x "$b" ] || { echo "missing $b (build first: scripts/build.sh)" >&2; exit 1; }
done
command -v python3 >/dev/null || { echo "python3 is needed to read stats.json" >&2; exit 1; }
mkdir -p "$out"

# run_odo SCANS RESULT_DIR MODE [extra args...]: odometry unless RESULT_DIR/stats.json exists.
run_odo() {
  local scans=$1 res=$2 mode=$3
  shift 3
  if [ ! -f "$res/stats.json" ]; then
    echo "== litamin2-odometry --mode $mode $* -o $res $scans" >&2
    rm -rf "$res"
    # Exit 3 means some frames could not be registered: a result (counted in stats.json as
    # registration_failures), not an error of the run.
    "$odo" --mode "$mode" "$@" -o "$res" "$scans" >&2 || [ $? -eq 3 ]
  fi
}

for s in $seqs; do
  scans="$out/scans/$s"
  need=0
  for m in icp cov; do [ -f "$out/${s}_$m/stats.json" ] || need=1; done
  if [ "$s" = "$sweep_seq" ]; then
    for v in $voxels; do
      for m in icp cov; do [ -f "$out/sweep/${s}_${m}_v$v/stats.json" ] || need=1; done
    done
  fi
  [ $need = 1 ] || continue
  if [ ! -f "$scans/times.txt" ]; then
    echo "== litamin2-sim --trajectory $poses/$s.txt --sequence $s --frames 0:$frames" >&2
    rm -rf "$scans"
    "$sim" --trajectory "$poses/$s.txt" --sequence "$s" --frames "0:$frames" --output "$scans" >&2
  fi
  run_odo "$scans" "$out/${s}_icp" icp
  run_odo "$scans" "$out/${s}_cov" icp+cov
  if [ "$s" = "$sweep_seq" ]; then
    for v in $voxels; do
      run_odo "$scans" "$out/sweep/${s}_icp_v$v" icp --voxel-size "$v"
      run_odo "$scans" "$out/sweep/${s}_cov_v$v" icp+cov --voxel-size "$v"
    done
  fi
  [ "${KEEP_SCANS:-0}" = 1 ] || rm -rf "$scans"
done

python3 - "$out" "$frames" "$sweep_seq" "$seqs" "$voxels" <<'EOF' | tee "$out/results.md"
import json, os, sys
out, frames, sweep_seq, seqs, voxels = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4].split(), sys.argv[5].split()
def load(p):
    with open(os.path.join(out, p, "stats.json")) as f:
        return json.load(f)
def num(x, fmt):
    return "n/a" if x is None else format(x, fmt)
print(f"Simulated KITTI sequences, frames 0:{frames} (partial), 3 m voxels (default config)\n")
print("| seq | mode | translation % | rotation deg/100 m | ATE m | frames/s |")
print("|---|---|---|---|---|---|")
acc = {"icp": [], "icp+cov": []}
for s in seqs:
    for m, d in (("icp", "icp"), ("icp+cov", "cov")):
        st = load(f"{s}_{d}")
        a = st["accuracy"]
        acc[m].append((a["kitti_translation_percent"], a["kitti_rotation_deg_per_100m"],
                       a["ate_translation_m"], st["frames_per_second"]))
        print(f"| {s} | {m} | {num(a['kitti_translation_percent'], '.3f')} | "
              f"{num(a['kitti_rotation_deg_per_100m'], '.4f')} | {num(a['ate_translation_m'], '.3f')} | "
              f"{st['frames_per_second']:.0f} |")
for m in ("icp", "icp+cov"):
    cols = list(zip(*acc[m]))
    mean = [None if any(v is None for v in c) else sum(c) / len(c) for c in cols]
    print(f"| **mean** | {m} | {num(mean[0], '.3f')} | {num(mean[1], '.4f')} | "
          f"{num(mean[2], '.3f')} | {num(mean[3], '.0f')} |")
print(f"\nVoxel-size sweep, simulated KITTI {sweep_seq} frames 0:{frames}\n")
print("| voxel m | mode | translation % | rotation deg/100 m | ATE m | frames/s | distributions/scan |")
print("|---|---|---|---|---|---|---|")
for v in voxels:
    for m, d in (("icp", "icp"), ("icp+cov", "cov")):
        p = f"sweep/{sweep_seq}_{d}_v{v}"
        if not os.path.exists(os.path.join(out, p, "stats.json")):
            continue
        st = load(p)
        a = st["accuracy"]
        print(f"| {v} | {m} | {num(a['kitti_translation_percent'], '.3f')} | "
              f"{num(a['kitti_rotation_deg_per_100m'], '.4f')} | {num(a['ate_translation_m'], '.3f')} | "
              f"{st['frames_per_second']:.0f} | {st['mean_distributions_per_scan']:.0f} |")
EOF
