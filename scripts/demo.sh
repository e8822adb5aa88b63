#!/usr/bin/env bash
# The main job on its built-in default: installs what is missing, builds (Release), simulates a
# LiDAR drive (the simulator's built-in 310 m loop, HDL-64), runs LiTAMIN2 odometry on it in both
# cost modes, and prints accuracy (KITTI metric, ATE) and speed. Output in ${OUT:-out/demo}.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
bin="${BUILD_DIR:-$root/build}/tools"
out=${OUT:-$root/out/demo}
mkdir -p "$out"

if [ ! -f "$out/sequence/times.txt" ]; then
  echo "== simulating the built-in loop into $out/sequence"
  "$bin/sim/litamin2-sim" --builtin loop --output "$out/sequence"
fi
for mode in icp+cov icp; do
  echo "== litamin2-odometry --mode $mode"
  "$bin/odometry/litamin2-odometry" --mode "$mode" --output "$out/odometry_$mode" "$out/sequence"
done
echo "== litamin2-eval (icp+cov), plot in $out/trajectory.svg"
"$bin/eval/litamin2-eval" --gt "$out/sequence/poses.txt" --est "$out/odometry_icp+cov/poses_kitti_cam.txt" \
  --plot "$out/trajectory.svg"
