#!/usr/bin/python3
"""What a fleet map's error is made of, from litamin2-fleet-bench --trajectories DIR.

  fleet_map_errors.py DIR [--cell 200]

DIR holds <vehicle>.kitti and <vehicle>_gt.kitti (3x4 rows, the map frame). Printed:
- the map-frame ATE (RMS translation error, no alignment: the bench's ate_m), horizontal and
  vertical;
- the error after the best rigid 3D fit of every keyframe onto the truth (Kabsch, no scale):
  the map's shape, apart from how it sits and turns as a whole about its anchor; the fit's
  rotation, and the residual split into horizontal and vertical;
- per square cell of the ground truth (--cell metres), the mean residual and the RMS of the
  residuals about that mean: a smooth bend shows in the means, passes over one place that
  disagree (layers) in the scatter about them.
Needs python3-numpy (Debian). docs/benchmarks.md, "The map frame's keyframe held, and what the
ATE is made of".
"""
import argparse
import glob
import os
import sys

import numpy as np


def load(folder):
    estimate, truth = [], []
    for gt in sorted(glob.glob(os.path.join(folder, "*_gt.kitti"))):
        est = gt[: -len("_gt.kitti")] + ".kitti"
        e = np.loadtxt(est, ndmin=2)[:, [3, 7, 11]]
        t = np.loadtxt(gt, ndmin=2)[:, [3, 7, 11]]
        if len(e) != len(t):
            sys.exit(f"{est}: {len(e)} poses against {len(t)} in {gt}")
        estimate.append(e)
        truth.append(t)
    if not estimate:
        sys.exit(f"{folder}: no *_gt.kitti files")
    return np.vstack(estimate), np.vstack(truth)


def rigid_fit(estimate, truth):
    """Rotation R and the means such that R (estimate - mean_e) + mean_t fits truth best."""
    mean_e, mean_t = estimate.mean(0), truth.mean(0)
    u, _, vt = np.linalg.svd((estimate - mean_e).T @ (truth - mean_t))
    d = np.eye(3)
    d[2, 2] = np.sign(np.linalg.det(vt.T @ u.T))
    return vt.T @ d @ u.T, mean_e, mean_t


def rms(v):
    return float(np.sqrt((v**2).sum(1).mean()))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("folder", help="litamin2-fleet-bench --trajectories folder")
    parser.add_argument("--cell", type=float, default=200.0, help="cell edge, m")
    args = parser.parse_args()
    if args.cell <= 0:
        sys.exit("--cell must be positive")
    estimate, truth = load(args.folder)
    rotation, mean_e, mean_t = rigid_fit(estimate, truth)
    residual = (rotation @ (estimate - mean_e).T).T + mean_t - truth
    turn = np.degrees(np.arccos(np.clip((np.trace(rotation) - 1) / 2, -1, 1)))
    print(f"keyframes {len(estimate)}")
    error = estimate - truth
    print(f"map-frame ATE {rms(error):.3f} m: horizontal {rms(error[:, :2]):.3f} m, "
          f"vertical {rms(error[:, 2:]):.3f} m")
    print(f"after a rigid fit {rms(residual):.3f} m (rotation {turn:.3f} deg): "
          f"horizontal {rms(residual[:, :2]):.3f} m, vertical {rms(residual[:, 2:]):.3f} m")
    cells = np.floor(truth[:, :2] / args.cell).astype(np.int64)
    keys, inverse = np.unique(cells, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    scatter_sq, counted = 0.0, 0
    for k, (cx, cy) in enumerate(keys):
        r = residual[inverse == k]
        mean = r.mean(0)
        scatter_sq += float(((r - mean) ** 2).sum())
        counted += len(r)
        print(f"cell x {cx * args.cell:7.0f} y {cy * args.cell:7.0f}: {len(r):7d} keyframes, "
              f"mean residual ({mean[0]:+.2f}, {mean[1]:+.2f}, {mean[2]:+.2f}) m")
    print(f"scatter about the cell means {np.sqrt(scatter_sq / counted):.3f} m RMS")


if __name__ == "__main__":
    main()
