#!/usr/bin/env python3
"""Each vehicle's current pose in the map frame, as litamin2-aggregator published it live on
rt/<stream>/map_odom, against the ground truth in the first vehicle's frame.

Inputs: the simulated fleet folder (vehicle_XX/{poses.txt,times.txt,calib.txt}, fleet.txt) and
the files map_odom_probe wrote (<prefix><stream>.txt: stamp frame_id child x y z qx qy qz qw).
Every message in the "map" frame is compared, without alignment, with the ground truth of the
frame with the nearest stamp (fleet_report.py's conventions).

Usage: map_odom_report.py FLEET_DIR PREFIX BOUND_M
Exit 1 if a stream has no message in the map frame or an error exceeds BOUND_M.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fleet_report import from_row, from_tum, inverse, mat_mul, read_rows, velo_to_cam  # noqa: E402


def main():
    fleet, prefix, bound = sys.argv[1], sys.argv[2], float(sys.argv[3])
    starts = {r[0]: from_row(r[1:13]) for r in read_rows(os.path.join(fleet, "fleet.txt"))}
    ok = True
    print("  %-12s %9s %12s %s" % ("stream", "messages", "in map frame",
                                  "error vs ground truth in the map frame: median / max / last"))
    for stream in sorted(starts):
        path = prefix + stream + ".txt"
        rows = read_rows(path) if os.path.exists(path) else []
        seq = os.path.join(fleet, stream)
        tr = velo_to_cam(os.path.join(seq, "calib.txt"))
        tr_inv = inverse(tr)
        times = [float(r[0]) for r in read_rows(os.path.join(seq, "times.txt"))]
        gt_cam = [from_row(r) for r in read_rows(os.path.join(seq, "poses.txt"))]
        errors = []
        for row in rows:
            if row[1] != "map":
                continue
            stamp = float(row[0])
            i = min(range(len(times)), key=lambda k: abs(times[k] - stamp))
            gt_map = mat_mul(starts[stream], mat_mul(mat_mul(tr_inv, gt_cam[i]), tr))
            est = from_tum([float(x) for x in row[3:10]])
            errors.append(math.dist([est[k][3] for k in range(3)], [gt_map[k][3] for k in range(3)]))
        if not errors:
            print("  %-12s %9d %12d no map-frame pose" % (stream, len(rows), 0))
            ok = False
            continue
        s = sorted(errors)
        print("  %-12s %9d %12d %.3f / %.3f / %.3f m" % (stream, len(rows), len(errors),
                                                       s[len(s) // 2], s[-1], errors[-1]))
        if s[-1] > bound:
            ok = False
    print("  (rt/<stream>/map_odom: corrected latest keyframe x inverse(its odometry) x odometry,\n"
          "   published live; no alignment; bound %.2f m)" % bound)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
