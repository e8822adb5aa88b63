#!/usr/bin/env bash
# tools/eval/frame_bias.py (docs/accuracy.md, "In-plane offsets") on paths with a known answer:
# a path whose every step turns 0.001 deg more about x than the truth shows that mean about x
# and nothing else; the truth itself shows zeros; bad input is refused.
set -euo pipefail
work=$1
tool=$(cd "$(dirname "$0")/../.." && pwd)/tools/eval/frame_bias.py
rm -rf "$work"; mkdir -p "$work"
/usr/bin/python3 - "$work" <<'PY'
import sys, numpy as np
work = sys.argv[1]
def rot_x(deg):
    a = np.radians(deg); c, s = np.cos(a), np.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
def rot_y(deg):
    a = np.radians(deg); c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
gt, est = [np.eye(4)], [np.eye(4)]
rng = np.random.default_rng(3)
for i in range(200):
    step = np.eye(4); step[:3, :3] = rot_y(rng.uniform(-2, 2)); step[:3, 3] = [0, 0, 1.0]
    gt.append(gt[-1] @ step)
    # The estimated step = the true step followed by a 0.001 deg turn about x.
    bias = np.eye(4); bias[:3, :3] = rot_x(-0.001)
    est.append(est[-1] @ step @ bias)
np.savetxt(work + "/gt.txt", np.array([p[:3].reshape(12) for p in gt]))
np.savetxt(work + "/est.txt", np.array([p[:3].reshape(12) for p in est]))
PY
out=$("$tool" "$work/gt.txt" "$work/est.txt" "$work/gt.txt")
echo "$out"
/usr/bin/python3 - "$out" <<'PY'
import sys
rows = [l.split() for l in sys.argv[1].splitlines()[1:]]
assert len(rows) == 2, rows
biased, truth = rows
# Columns: name (pairs) x +- sx y +- sy z +- sz | tx / ty / tz
assert abs(float(biased[2]) - 0.001) < 1e-6, biased
assert abs(float(biased[5])) < 1e-6 and abs(float(biased[8])) < 1e-6, biased
assert all(abs(float(truth[k])) < 1e-9 for k in (2, 5, 8)), truth
print("frame_bias: bias found, truth clean")
PY
# Bad input: no estimate, a file that is not poses, different lengths.
set +e
"$tool" "$work/gt.txt" > /dev/null 2>&1; [ $? -eq 2 ] || { echo "usage not refused"; exit 1; }
echo "not a pose" > "$work/bad.txt"
"$tool" "$work/gt.txt" "$work/bad.txt" > /dev/null 2>&1; [ $? -eq 1 ] || { echo "bad file accepted"; exit 1; }
head -5 "$work/est.txt" > "$work/short.txt"
"$tool" "$work/gt.txt" "$work/short.txt" > /dev/null 2>&1; [ $? -eq 1 ] || { echo "lengths accepted"; exit 1; }
echo "frame_bias: bad input refused"
