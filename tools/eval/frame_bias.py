#!/usr/bin/python3
"""The mean error of each frame-to-frame motion: a bias that repeats at every frame.

  frame_bias.py GT.txt EST.txt [EST2.txt ...]

GT and EST are KITTI pose files (3x4 rows, one per frame, the same frames), e.g. a simulated
sequence's poses.txt and litamin2-odometry's poses_kitti_cam.txt. For each consecutive pair the
error of the estimated motion, E = inv(inv(E_i) E_i+1) inv(G_i) G_i+1, is taken as a small
rotation vector (deg) and a translation (mm) in the frame of pose i; printed per estimate: the
mean over all pairs of each component and its standard error (sd / sqrt(pairs)). A drift that
grows at every frame shows as a mean several standard errors from 0; noise does not. In KITTI's
camera frame (x right, y down, z forward) a rotation about x is pitch, about y yaw, about z roll.
A mean pitch error of p deg a frame over a step of s m a frame is a rotation drift of about
100 p / s deg per 100 m. docs/accuracy.md, "In-plane offsets". Needs python3-numpy (Debian).
"""
import os
import sys

import numpy as np


def load(path):
    try:
        rows = np.loadtxt(path, ndmin=2)
    except (OSError, ValueError) as error:
        sys.exit("frame_bias.py: cannot read %s: %s" % (path, error))
    if rows.shape[1] != 12 or not np.all(np.isfinite(rows)):
        sys.exit("frame_bias.py: %s: expected 12 finite numbers a row (KITTI 3x4 poses)" % path)
    poses = np.tile(np.eye(4), (len(rows), 1, 1))
    poses[:, :3, :] = rows.reshape(-1, 3, 4)
    return poses


def motion_errors(gt, est):
    errors = []
    for i in range(len(gt) - 1):
        truth = np.linalg.inv(gt[i]) @ gt[i + 1]
        estimate = np.linalg.inv(est[i]) @ est[i + 1]
        e = np.linalg.inv(estimate) @ truth
        r = e[:3, :3]
        rotation = np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]]) / 2.0
        errors.append(np.r_[np.degrees(rotation), 1000.0 * e[:3, 3]])
    return np.array(errors)


def main(argv):
    if len(argv) < 3 or argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2
    gt = load(argv[1])
    print("%-40s %26s %26s %26s | translation mm x / y / z" %
          ("estimate (pairs)", "rotation deg about x", "about y", "about z"))
    for path in argv[2:]:
        est = load(path)
        if len(est) != len(gt):
            sys.exit("frame_bias.py: %s has %d poses, %s has %d" % (path, len(est), argv[1], len(gt)))
        if len(gt) < 3:
            sys.exit("frame_bias.py: need at least 3 poses")
        e = motion_errors(gt, est)
        mean = e.mean(axis=0)
        sem = e.std(axis=0, ddof=1) / np.sqrt(len(e))
        name = "%s (%d)" % (os.path.join(os.path.basename(os.path.dirname(path)),
                                         os.path.basename(path))[-32:], len(e))
        print("%-40s %+12.6f +- %-10.6f %+12.6f +- %-10.6f %+12.6f +- %-10.6f | %+.3f / %+.3f / %+.3f"
              % (name, mean[0], sem[0], mean[1], sem[1], mean[2], sem[2], mean[3], mean[4], mean[5]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
