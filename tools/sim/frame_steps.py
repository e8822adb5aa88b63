#!/usr/bin/env python3
"""Frame-to-frame agreement of an estimated path with the ground truth (KITTI 3x4 rows, one
per frame, same frames and frame convention, e.g. DIR/poses_kitti_cam.txt and SEQ/poses.txt).

usage: frame_steps.py EST GT [--json] [--breaks-over M]
prints: p50/p95/max translation error (m) and rotation error (deg) of the relative motions
inv(P_i) P_{i+1}, the largest step of EST and of GT (m), and the frames whose translation
error exceeds 1 m ("jumps"). --breaks-over M leaves out the steps whose ground-truth motion is
longer than M metres (breaks in the input that no scan can tell, e.g. litamin2-sim
--drop-bursts with long bursts) and counts them as "breaks". Rotation angles come from the skew part of the rotation
(atan2), so the ground truth's non-orthonormal rows (KITTI's are orthonormal only to ~1e-6)
do not add a ~0.1 deg floor as acos(trace) does. Plain Python, no numpy.
"""
import json
import math
import sys


def load(path):
    rows = [list(map(float, l.split())) for l in open(path) if l.strip()]
    for r in rows:
        if len(r) != 12:
            sys.exit(f"{path}: expected 12 numbers a line")
    return [[r[0:4], r[4:8], r[8:12], [0.0, 0.0, 0.0, 1.0]] for r in rows]


def inv(T):
    R = [[T[j][i] for j in range(3)] for i in range(3)]
    t = [-sum(R[i][k] * T[k][3] for k in range(3)) for i in range(3)]
    return [R[0] + [t[0]], R[1] + [t[1]], R[2] + [t[2]], [0.0, 0.0, 0.0, 1.0]]


def mul(A, B):
    return [[sum(A[i][k] * B[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def angle_deg(T):
    s = 0.5 * math.sqrt((T[2][1] - T[1][2]) ** 2 + (T[0][2] - T[2][0]) ** 2 + (T[1][0] - T[0][1]) ** 2)
    c = 0.5 * (T[0][0] + T[1][1] + T[2][2] - 1.0)
    return math.degrees(math.atan2(s, c))


def norm_t(T):
    return math.sqrt(sum(T[k][3] ** 2 for k in range(3)))


def q(v, f):
    s = sorted(v)
    return s[min(len(s) - 1, int(f * (len(s) - 1) + 0.5))] if s else float("nan")


def main():
    argv = sys.argv[1:]
    breaks_over = None
    if "--breaks-over" in argv:
        k = argv.index("--breaks-over")
        try:
            breaks_over = float(argv[k + 1])
        except (IndexError, ValueError):
            sys.exit("--breaks-over needs a length in metres")
        if not breaks_over > 0.0:
            sys.exit("--breaks-over needs a length above 0")
        del argv[k:k + 2]
    args = [a for a in argv if not a.startswith("--")]
    if len(args) != 2:
        sys.exit(__doc__)
    est, gt = load(args[0]), load(args[1])
    if len(est) != len(gt):
        sys.exit(f"{len(est)} estimated poses but {len(gt)} ground-truth poses")
    dt, dr, est_steps, gt_steps, jumps, breaks = [], [], [], [], [], 0
    for i in range(len(est) - 1):
        a = mul(inv(est[i]), est[i + 1])
        b = mul(inv(gt[i]), gt[i + 1])
        if breaks_over is not None and norm_t(b) > breaks_over:
            breaks += 1
            continue
        e = mul(inv(a), b)
        dt.append(norm_t(e))
        dr.append(angle_deg(e))
        est_steps.append(norm_t(a))
        gt_steps.append(norm_t(b))
        if dt[-1] > 1.0:
            jumps.append(i + 1)
    out = {
        "frames": len(est),
        "translation_error_m": {"p50": q(dt, 0.5), "p95": q(dt, 0.95), "max": max(dt, default=0)},
        "rotation_error_deg": {"p50": q(dr, 0.5), "p95": q(dr, 0.95), "max": max(dr, default=0)},
        "largest_step_m": {"estimate": max(est_steps, default=0), "ground_truth": max(gt_steps, default=0)},
        "jumps_over_1m": len(jumps),
        "first_jumps": jumps[:10],
    }
    if breaks_over is not None:
        out["breaks_left_out"] = breaks
    if "--json" in sys.argv:
        print(json.dumps(out, indent=1))
    else:
        t, r, s = out["translation_error_m"], out["rotation_error_deg"], out["largest_step_m"]
        print("translation error m p50 %.4f p95 %.4f max %.3f | rotation error deg p50 %.4f p95 %.4f "
              "max %.3f | largest step m est %.3f gt %.3f | jumps > 1 m: %d"
              % (t["p50"], t["p95"], t["max"], r["p50"], r["p95"], r["max"], s["estimate"],
                 s["ground_truth"], out["jumps_over_1m"]))


if __name__ == "__main__":
    main()
