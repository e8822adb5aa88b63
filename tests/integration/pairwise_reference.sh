#!/usr/bin/env bash
# tools/eval/pairwise_reference.py (the scan-to-scan reference of docs/accuracy.md, "Breaks that
# cannot be registered") on a short simulated VLP-16 run of the built-in loop: every pair is
# registrable and within 5 cm / 0.3 deg of the simulator's motion; `compare` counts no pair off
# for the ground truth itself and every pair for a path standing still; bad input is refused.
set -euo pipefail
tools=$1; work=$2
ref=$(cd "$(dirname "$0")/../.." && pwd)/tools/eval/pairwise_reference.py
rm -rf "$work"; mkdir -p "$work"
"$tools/sim/litamin2-sim" --builtin loop --sensor vlp16 --frames 0:6 --threads 1 \
  --output "$work/seq" 2>/dev/null
"$ref" make "$work/seq" "$work/ref.txt" 2>/dev/null
# The ground truth in the LiDAR's frame (poses.txt is camera 0's: T_velo = Tr^-1 P Tr).
/usr/bin/python3 - "$work" <<'PY'
import sys, numpy as np
work = sys.argv[1]
tr = [l.split()[1:] for l in open(work + "/seq/calib.txt") if l.startswith("Tr:")][0]
Tr = np.vstack([np.array(tr, float).reshape(3, 4), [0, 0, 0, 1]])
P = np.loadtxt(work + "/seq/poses.txt").reshape(-1, 3, 4)
velo = [np.linalg.inv(Tr) @ np.vstack([p, [0, 0, 0, 1]]) @ Tr for p in P]
np.savetxt(work + "/gt_velo.txt", np.array([v[:3].reshape(12) for v in velo]))
np.savetxt(work + "/still.txt", np.array([np.eye(4)[:3].reshape(12) for _ in velo]))
worst_t = worst_r = 0.0
lines = [l.split() for l in open(work + "/ref.txt")]
assert len(lines) == len(P) - 1, "one line per pair"
for w in lines:
    i = int(w[0]); dx, dy, dz, yaw, median, inliers = map(float, w[1:])
    truth = np.linalg.inv(velo[i - 1]) @ velo[i]
    assert median < 0.25 and inliers > 0.4, "pair %d not registrable: %s" % (i, w)
    worst_t = max(worst_t, np.linalg.norm(truth[:3, 3] - [dx, dy, dz]))
    worst_r = max(worst_r, abs(np.degrees(np.arctan2(truth[1, 0], truth[0, 0])) - yaw))
print("pairwise reference vs simulated motion: worst %.3f m, %.3f deg" % (worst_t, worst_r))
assert worst_t < 0.05 and worst_r < 0.3
PY
out=$("$ref" compare "$work/ref.txt" truth="$work/gt_velo.txt" still="$work/still.txt")
echo "$out"
grep -q "^registrable pairs: 5 of 5" <<<"$out"
grep -q "^truth: .*pairs > 0.5 m off: 0 of 5" <<<"$out"
grep -q "^still: .*pairs > 0.5 m off: 5 of 5" <<<"$out"
# Bad input: a folder without scans, a path that is not KITTI rows, an unknown command.
mkdir -p "$work/empty"; echo "1 2 3" > "$work/bad.txt"
for args in "make $work/empty $work/x.txt" "compare $work/ref.txt bad=$work/bad.txt" "frobnicate"; do
  # shellcheck disable=SC2086
  if "$ref" $args > "$work/err.txt" 2>&1; then echo "accepted: $args"; exit 1; fi
  grep -q "pairwise_reference.py: " "$work/err.txt" || { cat "$work/err.txt"; exit 1; }
done
echo "1 passed, 0 failed"
