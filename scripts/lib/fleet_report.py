#!/usr/bin/env python3
"""Per-stream accuracy of a fleet run before and after loop closure, and the merge check.

Inputs: the simulated fleet folder (vehicle_XX/{poses.txt,times.txt,calib.txt}, fleet.txt), the
odometry litamin2d published (KITTI rows of every frame, one file per stream), and the
aggregator's export (<stream>_tum.txt corrected keyframe poses, frames.txt). For each stream it
writes, at the keyframes' stamps, the ground truth, the odometry and the corrected poses as
KITTI files (sensor frame; <stream>_gt_map_keyframes.txt: the ground truth in the first
vehicle's frame, for plots of merged streams) and evaluates them with litamin2-eval (drift and SE(3)-aligned ATE).
Merge check: streams that ended in the map frame are compared, without any alignment, with the
ground truth of the sensor in the first vehicle's frame (fleet.txt start poses).

Usage: fleet_report.py EVAL_TOOL FLEET_DIR ODOMETRY_PREFIX EXPORT_DIR OUT_DIR MERGE_BOUND_M
Exit 1 if a stream is missing or the merge error exceeds MERGE_BOUND_M.
"""
import json
import math
import os
import subprocess
import sys


def mat_mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def inverse(m):
    r = [[m[j][i] for j in range(3)] for i in range(3)]
    t = [-sum(r[i][k] * m[k][3] for k in range(3)) for i in range(3)]
    return [r[0] + [t[0]], r[1] + [t[1]], r[2] + [t[2]], [0.0, 0.0, 0.0, 1.0]]


def from_row(values):
    v = [float(x) for x in values]
    return [v[0:4], v[4:8], v[8:12], [0.0, 0.0, 0.0, 1.0]]


def to_row(m):
    return " ".join("%.9e" % m[i][j] for i in range(3) for j in range(4))


def from_tum(q):
    tx, ty, tz, qx, qy, qz, qw = q
    return [[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw), tx],
            [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw), ty],
            [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy), tz],
            [0.0, 0.0, 0.0, 1.0]]


def read_rows(path):
    with open(path) as f:
        return [line.split() for line in f if line.strip() and not line.startswith("#")]


def velo_to_cam(calib_path):
    for row in read_rows(calib_path):
        if row[0] == "Tr:":
            return from_row(row[1:13])
    raise SystemExit("no Tr: in " + calib_path)


def rotation_deg(a, b):
    trace = sum(a[k][i] * b[k][i] for i in range(3) for k in range(3))
    return math.degrees(math.acos(max(-1.0, min(1.0, (trace - 1.0) / 2.0))))


def evaluate(tool, gt, est):
    out = subprocess.run([tool, "--gt", gt, "--est", est, "--json"], check=True,
                         capture_output=True, text=True).stdout
    j = json.loads(out)
    kitti = j["kitti"]
    drift = kitti["translation_percent"] if kitti.get("valid") else float("nan")
    return drift, j["ate"]["translation_rmse_m"]


def main():
    tool, fleet, odometry_prefix, export, out, bound = sys.argv[1:7]
    bound = float(bound)
    os.makedirs(out, exist_ok=True)
    starts = {r[0]: from_row(r[1:13]) for r in read_rows(os.path.join(fleet, "fleet.txt"))}
    frames = {r[0]: (r[1], r[2] == "1") for r in read_rows(os.path.join(export, "frames.txt"))}
    ok = True
    print("  %-12s %9s %-22s %-22s %s" % ("stream", "keyframes", "odometry drift / ATE",
                                         "with loops drift / ATE", "map frame error"))
    for stream in sorted(starts):
        seq = os.path.join(fleet, stream)
        tum_path = os.path.join(export, stream + "_tum.txt")
        if stream not in frames or not os.path.exists(tum_path):
            print("  %s: no keyframes in the aggregator's export" % stream)
            ok = False
            continue
        tr = velo_to_cam(os.path.join(seq, "calib.txt"))
        tr_inv = inverse(tr)
        times = [float(r[0]) for r in read_rows(os.path.join(seq, "times.txt"))]
        gt_cam = [from_row(r) for r in read_rows(os.path.join(seq, "poses.txt"))]
        odometry = [from_row(r) for r in read_rows(odometry_prefix + stream + ".txt")]
        corrected = read_rows(tum_path)
        gt_rows, gt_map_rows, odo_rows, slam_rows = [], [], [], []
        worst_t = worst_r = 0.0
        for row in corrected:
            stamp = float(row[0])
            i = min(range(len(times)), key=lambda k: abs(times[k] - stamp))
            gt = mat_mul(mat_mul(tr_inv, gt_cam[i]), tr)  # sensor pose in its first frame
            est = from_tum([float(x) for x in row[1:8]])
            gt_rows.append(to_row(gt))
            odo_rows.append(to_row(odometry[i]))
            slam_rows.append(to_row(est))
            # In the map frame (the first vehicle's start): compare with the start pose moved.
            gt_map = mat_mul(starts[stream], gt)
            gt_map_rows.append(to_row(gt_map))
            worst_t = max(worst_t, math.dist([est[k][3] for k in range(3)],
                                             [gt_map[k][3] for k in range(3)]))
            worst_r = max(worst_r, rotation_deg(est, gt_map))
        files = {}
        for name, rows in (("gt", gt_rows), ("gt_map", gt_map_rows), ("odometry", odo_rows),
                           ("slam", slam_rows)):
            files[name] = os.path.join(out, "%s_%s_keyframes.txt" % (stream, name))
            with open(files[name], "w") as f:
                f.write("\n".join(rows) + "\n")
        odo = evaluate(tool, files["gt"], files["odometry"])
        slam = evaluate(tool, files["gt"], files["slam"])
        in_map = frames[stream][1]
        merge = ("max %.2f m / %.2f deg" % (worst_t, worst_r)) if in_map else \
            "not merged (frame of %s)" % frames[stream][0]
        if not in_map or worst_t > bound:
            ok = False
        def drift(d):
            return "  n/a" if math.isnan(d) else "%5.2f" % d
        print("  %-12s %9d %s %% / %6.3f m      %s %% / %6.3f m      %s" %
              (stream, len(corrected), drift(odo[0]), odo[1], drift(slam[0]), slam[1], merge))
    print("  (drift: KITTI metric at the keyframes, n/a under 100 m; ATE after SE(3) alignment;\n"
          "   map frame error: corrected keyframes vs ground truth in the first vehicle's frame,\n"
          "   no alignment, bound %.2f m)" % bound)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
