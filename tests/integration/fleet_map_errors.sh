#!/usr/bin/env bash
# tools/eval/fleet_map_errors.py (docs/benchmarks.md, "The map frame's keyframe held, and what
# the ATE is made of") on trajectories whose answer is known:
#  1. a map turned by 1 degree and shifted as a whole: the map-frame ATE is the RMS of the
#     offsets, the rigid fit finds the 1 degree turn and leaves nothing, no scatter, and every
#     keyframe's heading is 1 degree off;
#  2. two vehicles over the same places, one 1.5 m to the side of the other (two layers): the
#     rigid fit leaves 0.75 m, all of it scatter about the cell means, and no turn; the pairs
#     of the two passes at one place are 1.5 m apart in the map, and --store tells whether
#     loops tie them (a store whose loops join the two at every keyframe, and one without);
#  3. bad input (no trajectories, rows that do not pair up, a cell of 0, a missing store) is
#     refused.
# Usage: fleet_map_errors.sh WORK_DIR
set -euo pipefail
work=$1
tool=$(cd "$(dirname "$0")/../.." && pwd)/tools/eval/fleet_map_errors.py
rm -rf "$work"
mkdir -p "$work/turned" "$work/layers" "$work/empty" "$work/short"

/usr/bin/python3 - "$work" <<'PY'
import sys
import numpy as np

work = sys.argv[1]
rng = np.random.default_rng(7)


def rows(positions, yaw_deg=0.0):
    c, s = np.cos(np.radians(yaw_deg)), np.sin(np.radians(yaw_deg))
    out = []
    for p in positions:
        out.append([c, -s, 0, p[0], s, c, 0, p[1], 0, 0, 1, p[2]])
    return np.array(out)


truth = np.column_stack([rng.uniform(0, 400, 300), rng.uniform(0, 400, 300),
                         rng.uniform(-1, 1, 300)])
# 1: every keyframe turned by 1 degree about the origin and shifted by (2, -1, 0.5).
turn = np.radians(1.0)
R = np.array([[np.cos(turn), -np.sin(turn), 0], [np.sin(turn), np.cos(turn), 0], [0, 0, 1]])
estimate = truth @ R.T + np.array([2.0, -1.0, 0.5])
for v, part in enumerate(np.array_split(np.arange(len(truth)), 2)):
    np.savetxt(f"{work}/turned/v{v}_gt.kitti", rows(truth[part]))
    np.savetxt(f"{work}/turned/v{v}.kitti", rows(estimate[part], 1.0))
ate = np.sqrt(((estimate - truth) ** 2).sum(1).mean())
open(f"{work}/turned/expected_ate", "w").write(f"{ate:.3f}\n")
# 2: vehicle 0 exact, vehicle 1 over the same places 1.5 m off in y.
np.savetxt(f"{work}/layers/v0_gt.kitti", rows(truth))
np.savetxt(f"{work}/layers/v0.kitti", rows(truth))
np.savetxt(f"{work}/layers/v1_gt.kitti", rows(truth))
np.savetxt(f"{work}/layers/v1.kitti", rows(truth + np.array([0.0, 1.5, 0.0])))
import sqlite3
for name, tied in (("tied", True), ("untied", False)):
    db = sqlite3.connect(f"{work}/{name}.db")
    db.execute("CREATE TABLE loop_edges (from_stream TEXT, from_id INTEGER, to_stream TEXT, "
               "to_id INTEGER)")
    if tied:
        db.executemany("INSERT INTO loop_edges VALUES ('v0', ?, 'v1', ?)",
                       [(k, k) for k in range(len(truth))])
    db.commit()
    db.close()
# 3: an estimate one row short of its truth.
np.savetxt(f"{work}/short/v0_gt.kitti", rows(truth[:10]))
np.savetxt(f"{work}/short/v0.kitti", rows(truth[:9]))
PY

echo "== 1: a turned and shifted map"
out=$(/usr/bin/python3 "$tool" "$work/turned" --anchor-headings 20)
echo "$out"
grep -q "^keyframes 300$" <<<"$out"
[ "$(grep -c "^  keyframe .* from the anchor): +1.000; others" <<<"$out")" -eq 4 ]
grep -q "^map-frame ATE $(cat "$work/turned/expected_ate") m" <<<"$out"
grep -q "^after a rigid fit 0.000 m (rotation 1.000 deg)" <<<"$out"
grep -q "^scatter about the cell means 0.000 m RMS$" <<<"$out"

echo "== 2: two layers 1.5 m apart"
out=$(/usr/bin/python3 "$tool" "$work/layers" --cell 100 --store "$work/tied.db")
echo "$out"
grep -q "^map-frame ATE 1.061 m: horizontal 1.061 m, vertical 0.000 m$" <<<"$out"
grep -q "^after a rigid fit 0.750 m (rotation 0.000 deg): horizontal 0.750 m" <<<"$out"
grep -q "^scatter about the cell means 0.750 m RMS$" <<<"$out"
grep -q "^pairs of two passes within 1 m: .* p50 1.500 .* over 1 m 100.0 %" <<<"$out"
tied=$(sed -n 's/^pairs tied by a loop within 15 keyframes: within 1 m: none, over 1 m \([0-9]*\) % of.*/\1/p' <<<"$out")
[ -n "$tied" ] && [ "$tied" -ge 95 ] || { echo "pairs the loops tie not found"; exit 1; }
out=$(/usr/bin/python3 "$tool" "$work/layers" --store "$work/untied.db")
grep -q "^pairs tied by a loop within 15 keyframes: within 1 m: none, over 1 m 0 % of" <<<"$out"
# Every cell's mean residual is zero: the layers straddle the fit.
cells=$(grep -c "^cell" <<<"$out")
zero=$(grep -cE "^cell .* mean residual \([+-]0\.00, [+-]0\.00, [+-]0\.00\) m$" <<<"$out")
[ "$cells" -gt 1 ] && [ "$zero" -eq "$cells" ] || { echo "cell means not zero"; exit 1; }

echo "== 3: bad input"
if /usr/bin/python3 "$tool" "$work/empty" 2>"$work/err"; then echo "empty folder accepted"; exit 1; fi
grep -q "no \*_gt.kitti files" "$work/err"
if /usr/bin/python3 "$tool" "$work/short" 2>"$work/err"; then echo "short rows accepted"; exit 1; fi
grep -q "9 poses against 10" "$work/err"
if /usr/bin/python3 "$tool" "$work/turned" --cell 0 2>"$work/err"; then echo "cell 0 accepted"; exit 1; fi
grep -q "must be positive" "$work/err"
if /usr/bin/python3 "$tool" "$work/turned" --store "$work/none.db" 2>"$work/err"; then
  echo "missing store accepted"; exit 1
fi
grep -q "no such store" "$work/err"
if /usr/bin/python3 "$tool" "$work/turned" --anchor-headings -1 2>"$work/err"; then
  echo "negative --anchor-headings accepted"; exit 1
fi
grep -q "must be >= 0" "$work/err"
echo "fleet_map_errors.py: all checks passed"
