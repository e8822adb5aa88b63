#!/usr/bin/env bash
# litamin2 and KISS-ICP side by side on simulated KITTI drives, one evaluator, one thread each
# (issue 12's targets; docs/accuracy.md, "Side by side with KISS-ICP"). Simulates each
# sequence once, runs both odometries on the same scans, scores both with litamin2-eval (KITTI
# drift) and tools/sim/frame_steps.py (frame-to-frame error, jumps > 1 m), and prints a
# markdown table with litamin2 / KISS-ICP ratios (also written to OUT/results.md).
#
# Usage: scripts/peers/side-by-side.sh OUT
# Env:
#   KISS_ICP_RUNNER  kiss_icp_runner built by scripts/peers/build-kiss-icp.sh (required)
#   SEQS       sequences (default "00 01 05 07 08"); POSES folder of KITTI NN.txt
#              (default /work/shared/data/kitti/poses); CALIB (default
#              /work/shared/data/kitti/calib_Tr_velo_to_cam.txt)
#   SENSORS    default "hdl64 vlp16"
#   FRAMES     frames 0:FRAMES of each sequence (default 1000)
#   WORLD      name of the simulated world (default street) and WORLD_ARGS its litamin2-sim
#              options (default "--realism street": motion within the sweep, self-hits, rough
#              ground, vegetation, traffic, dropped frames; docs/simulator.md). WORLD=old
#              WORLD_ARGS="" gives the default world.
#   DESKEW     1 (default) also runs litamin2-odometry --deskew (it reads the simulator's pcd/
#              scans with their t field)
#   PEER_DESKEW  1 also runs kiss_icp_runner --deskew (default 0, KISS-ICP's own default: its
#              deskew takes the last motion between files as the motion within one sweep, which
#              over-corrects where files were dropped, as in the street world)
#   LITAMIN2_ARGS  extra litamin2-odometry options (default none: the shipped defaults)
#   KEEP_SCANS=1 keeps the simulated scans (HDL-64: ~1.6 MB a frame)
#   BUILD_DIR  litamin2's build (default <repo>/build); builds nothing.
# Results already in OUT are reused, so an interrupted run continues where it stopped.
set -euo pipefail
case "${1:-}" in -h | --help | "") sed -n '2,29p' "$0" | sed 's/^# \{0,1\}//'; [ -n "${1:-}" ]; exit $? ;; esac
root=$(cd "$(dirname "$0")/../.." && pwd)
bin="${BUILD_DIR:-$root/build}/tools"
out=$1
kiss=${KISS_ICP_RUNNER:?set KISS_ICP_RUNNER to kiss_icp_runner (scripts/peers/build-kiss-icp.sh)}
seqs=${SEQS:-00 01 05 07 08}
sensors=${SENSORS:-hdl64 vlp16}
frames=${FRAMES:-1000}
world=${WORLD:-street}
world_args=${WORLD_ARGS---realism street}
deskew=${DESKEW:-1}
poses=${POSES:-/work/shared/data/kitti/poses}
calib=${CALIB:-/work/shared/data/kitti/calib_Tr_velo_to_cam.txt}
sim="$bin/sim/litamin2-sim"
odo="$bin/odometry/litamin2-odometry"
eval="$bin/eval/litamin2-eval"
steps="$root/tools/sim/frame_steps.py"
for b in "$sim" "$odo" "$eval" "$kiss"; do
  [ -x "$b" ] || { echo "missing $b" >&2; exit 1; }
done
mkdir -p "$out"

# score DIR SCANS: DIR/score.json from DIR/poses_kitti_cam.txt against SCANS/poses.txt.
score() {
  local dir=$1 scans=$2
  [ -f "$dir/score.json" ] && return
  "$eval" --gt "$scans/poses.txt" --est "$dir/poses_kitti_cam.txt" --json >"$dir/eval.json"
  python3 "$steps" "$dir/poses_kitti_cam.txt" "$scans/poses.txt" --json >"$dir/steps.json"
  python3 - "$dir" <<'EOF'
import json, os, sys
d = sys.argv[1]
e = json.load(open(os.path.join(d, "eval.json")))
s = json.load(open(os.path.join(d, "steps.json")))
st = json.load(open(os.path.join(d, "stats.json"))) if os.path.exists(os.path.join(d, "stats.json")) else {}
fps = st.get("frames_per_second")
json.dump({"translation_percent": e["kitti"]["translation_percent"],
           "rotation_deg_per_100m": e["kitti"]["rotation_deg_per_100m"],
           "step_error_m_p50": s["translation_error_m"]["p50"],
           "step_error_m_p95": s["translation_error_m"]["p95"],
           "jumps_over_1m": s["jumps_over_1m"], "frames": s["frames"],
           "largest_step_m": s["largest_step_m"]["estimate"],
           "largest_gt_step_m": s["largest_step_m"]["ground_truth"],
           "frames_per_s": fps}, open(os.path.join(d, "score.json"), "w"))
EOF
}

for seq in $seqs; do
  for sensor in $sensors; do
    name="${seq}_${sensor}_${world}_0-${frames}"
    scans="$out/scans/$name"
    runs="$out/runs/$name"
    methods="litamin2 kiss_icp"
    [ "$deskew" = 1 ] && methods="$methods litamin2_deskew"
    [ "${PEER_DESKEW:-0}" = 1 ] && methods="$methods kiss_icp_deskew"
    need=0
    for m in $methods; do [ -f "$runs/$m/score.json" ] || need=1; done
    [ $need = 1 ] || continue
    if [ ! -f "$scans/poses.txt" ]; then
      echo "== $name: litamin2-sim" >&2
      rm -rf "$scans"
      # shellcheck disable=SC2086 # WORLD_ARGS is a list of options
      nice "$sim" --trajectory "$poses/$seq.txt" --calib "$calib" --sequence "$seq" \
        --frames "0:$frames" --sensor "$sensor" --threads 1 $world_args --output "$scans" >&2
    fi
    mkdir -p "$runs"
    for m in $methods; do
      dir="$runs/$m"
      if [ ! -f "$dir/poses_kitti_cam.txt" ]; then
        echo "== $name: $m" >&2
        rm -rf "$dir"
        case $m in
          # Exit 3: some frames were not registered, counted in stats.json; still a result.
          # shellcheck disable=SC2086
          litamin2) "$odo" -q -j 1 ${LITAMIN2_ARGS:-} -o "$dir" "$scans" >&2 || [ $? -eq 3 ] ;;
          # shellcheck disable=SC2086
          litamin2_deskew) "$odo" -q -j 1 --deskew ${LITAMIN2_ARGS:-} -o "$dir" "$scans" >&2 || [ $? -eq 3 ] ;;
          kiss_icp) "$kiss" -q --threads 1 -o "$dir" "$scans" >&2 ;;
          kiss_icp_deskew) "$kiss" -q --threads 1 --deskew -o "$dir" "$scans" >&2 ;;
        esac
      fi
      score "$dir" "$scans"
    done
    [ "${KEEP_SCANS:-0}" = 1 ] || rm -rf "$scans/velodyne" "$scans/pcd"
  done
done

python3 - "$out" <<'EOF' | tee "$out/results.md"
import json, os, sys
out = sys.argv[1]
rows = []
runs = os.path.join(out, "runs")
print("| sequence | method | KITTI % | deg/100 m | step error m p50 / p95 | jumps > 1 m (steps) | largest step m est / gt | frames/s | KITTI % / KISS-ICP's |")
print("|---|---|---|---|---|---|---|---|---|")
for name in sorted(os.listdir(runs)):
    got = {}
    for m in ("litamin2", "kiss_icp", "litamin2_deskew", "kiss_icp_deskew"):
        p = os.path.join(runs, name, m, "score.json")
        if os.path.exists(p):
            got[m] = json.load(open(p))
    for m, s in got.items():
        peer = got.get("kiss_icp")  # KISS-ICP as shipped (deskew off)
        ratio = "" if m.startswith("kiss") or not peer or s["translation_percent"] is None \
            or not peer["translation_percent"] else \
            "%.2fx" % (s["translation_percent"] / peer["translation_percent"])
        f = lambda x, fmt: "n/a" if x is None else format(x, fmt)
        print(f"| {name} | {m} | {f(s['translation_percent'], '.3f')} | {f(s['rotation_deg_per_100m'], '.3f')} | "
              f"{s['step_error_m_p50']:.3f} / {s['step_error_m_p95']:.3f} | {s['jumps_over_1m']} ({s['frames'] - 1}) | "
              f"{s['largest_step_m']:.1f} / {s['largest_gt_step_m']:.1f} | {f(s['frames_per_s'], '.0f')} | {ratio} |")
EOF
