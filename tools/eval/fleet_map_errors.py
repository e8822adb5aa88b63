#!/usr/bin/python3
"""What a fleet map's error is made of, from litamin2-fleet-bench --trajectories DIR.

  fleet_map_errors.py DIR [--cell 200] [--store S.db] [--anchor-headings 120]

DIR holds <vehicle>.kitti and <vehicle>_gt.kitti (3x4 rows, the map frame). Printed:
- the map-frame ATE (RMS translation error, no alignment: the bench's ate_m), horizontal and
  vertical;
- the error after the best rigid 3D fit of every keyframe onto the truth (Kabsch, no scale):
  the map's shape, apart from how it sits and turns as a whole about its anchor; the fit's
  rotation, and the residual split into horizontal and vertical;
- per square cell of the ground truth (--cell metres), the mean residual and the RMS of the
  residuals about that mean: a smooth bend shows in the means, passes over one place that
  disagree (layers) in the scatter about them;
- layers measured directly: pairs of keyframes of two passes (two vehicles, or one vehicle
  more than 50 keyframes apart) within 1 m of each other in the truth, and how far the map
  puts them apart beyond the truth's offset (the 8 nearest of up to 20,000 random keyframes);
- with --store (the bench's store): of those pairs, the share that a loop edge ties directly
  (between the two vehicles, each end within 15 keyframes of its keyframe), for pairs the map
  puts within 1 m and for pairs it puts further apart.
- with --anchor-headings N: along the first vehicle's first N keyframes (the map frame's
  anchor), every 5th keyframe's heading error, and the mean heading error of the other
  passes' keyframes within 2 m of it in the truth: whether the first vehicle or the whole map
  turns there.
Row i of <vehicle>.kitti is the vehicle's keyframe i (the bench's ids).
Needs python3-numpy and python3-scipy (Debian). docs/benchmarks.md, "The map frame's keyframe
held, and what the ATE is made of" and "Layers".
"""
import argparse
import glob
import os
import sys

import numpy as np


def load(folder):
    """Positions of every keyframe (estimate, truth), each one's vehicle number and keyframe
    id, and the vehicles' names."""
    estimate, truth, heading, vehicle, ids, names = [], [], [], [], [], []
    for gt in sorted(glob.glob(os.path.join(folder, "*_gt.kitti"))):
        est = gt[: -len("_gt.kitti")] + ".kitti"
        e_rows = np.loadtxt(est, ndmin=2)
        t_rows = np.loadtxt(gt, ndmin=2)
        if len(e_rows) != len(t_rows):
            sys.exit(f"{est}: {len(e_rows)} poses against {len(t_rows)} in {gt}")
        e, t = e_rows[:, [3, 7, 11]], t_rows[:, [3, 7, 11]]
        # Heading error: the yaw of R_estimate R_truth^T.
        r_e, r_t = e_rows.reshape(-1, 3, 4)[:, :, :3], t_rows.reshape(-1, 3, 4)[:, :, :3]
        difference = np.einsum("nij,nkj->nik", r_e, r_t)
        heading.append(np.degrees(np.arctan2(difference[:, 1, 0], difference[:, 0, 0])))
        vehicle.append(np.full(len(t), len(names)))
        ids.append(np.arange(len(t)))
        names.append(os.path.basename(gt)[: -len("_gt.kitti")])
        estimate.append(e)
        truth.append(t)
    if not estimate:
        sys.exit(f"{folder}: no *_gt.kitti files")
    return (np.vstack(estimate), np.vstack(truth), np.concatenate(heading),
            np.concatenate(vehicle), np.concatenate(ids), names)


def pairs_at_one_place(estimate, truth, vehicle, ids, radius=1.0, samples=20000, seed=0):
    """Pairs (i, j) of keyframes of two passes within `radius` in the truth (the 8 nearest of up
    to `samples` random keyframes), and the map's offset between them beyond the truth's."""
    from scipy.spatial import cKDTree

    rng = np.random.default_rng(seed)
    queries = rng.choice(len(truth), min(samples, len(truth)), replace=False)
    distance, near = cKDTree(truth[:, :2]).query(truth[queries, :2], k=9,
                                                 distance_upper_bound=radius)
    i = np.repeat(queries, 9)
    j = near.reshape(-1)
    keep = np.isfinite(distance.reshape(-1)) & (j != i)
    i, j = i[keep], j[keep]
    two_passes = (vehicle[i] != vehicle[j]) | (np.abs(ids[i] - ids[j]) > 50)
    i, j = i[two_passes], j[two_passes]
    offset = np.linalg.norm((estimate[i] - estimate[j]) - (truth[i] - truth[j]), axis=1)
    return i, j, offset


def tied_by_a_loop(store, names, vehicle, ids, i, j, window=15):
    """For each pair, whether a loop edge of the store joins the two vehicles with each end
    within `window` keyframes of the pair's keyframe."""
    import sqlite3

    number = {name: n for n, name in enumerate(names)}
    loops = {}
    with sqlite3.connect(f"file:{store}?mode=ro", uri=True) as db:
        for a, ia, b, ib in db.execute("SELECT from_stream, from_id, to_stream, to_id "
                                       "FROM loop_edges"):
            if a in number and b in number:
                loops.setdefault((number[a], number[b]), []).append((ia, ib))
                loops.setdefault((number[b], number[a]), []).append((ib, ia))
    tied = np.zeros(len(i), dtype=bool)
    for k, (a, b) in enumerate(zip(i, j)):
        ka, kb = ids[a], ids[b]
        tied[k] = any(abs(x - ka) <= window and abs(y - kb) <= window
                      for x, y in loops.get((vehicle[a], vehicle[b]), ()))
    return tied


def rigid_fit(estimate, truth):
    """Rotation R and the means such that R (estimate - mean_e) + mean_t fits truth best."""
    mean_e, mean_t = estimate.mean(0), truth.mean(0)
    u, _, vt = np.linalg.svd((estimate - mean_e).T @ (truth - mean_t))
    d = np.eye(3)
    d[2, 2] = np.sign(np.linalg.det(vt.T @ u.T))
    return vt.T @ d @ u.T, mean_e, mean_t


def rms(v):
    return float(np.sqrt((v**2).sum(1).mean()))


def print_anchor_headings(truth, heading, vehicle, ids, names, count):
    """The first vehicle's heading error along its first `count` keyframes, and that of the
    other passes' keyframes within 2 m of each in the truth."""
    from scipy.spatial import cKDTree

    tree = cKDTree(truth[:, :2])
    first = np.flatnonzero(vehicle == 0)
    print(f"headings along {names[0]}'s first {min(count, len(first))} keyframes "
          "(error, deg; other passes within 2 m: mean, count):")
    for n in first[:count:5]:
        near = np.array(tree.query_ball_point(truth[n, :2], 2.0), dtype=np.int64)
        others = near[(vehicle[near] != 0) | (np.abs(ids[near] - ids[n]) > 50)]
        mean = f"{heading[others].mean():+.3f}" if len(others) else "none"
        print(f"  keyframe {ids[n]:5d} ({np.linalg.norm(truth[n, :2] - truth[first[0], :2]):6.1f} m "
              f"from the anchor): {heading[n]:+.3f}; others {mean}, {len(others)}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("folder", help="litamin2-fleet-bench --trajectories folder")
    parser.add_argument("--cell", type=float, default=200.0, help="cell edge, m")
    parser.add_argument("--store", help="the bench's store: which pairs a loop ties")
    parser.add_argument("--anchor-headings", type=int, default=0, metavar="N",
                        help="heading errors along the first vehicle's first N keyframes")
    args = parser.parse_args()
    if args.cell <= 0:
        sys.exit("--cell must be positive")
    if args.store and not os.path.isfile(args.store):
        sys.exit(f"{args.store}: no such store")
    if args.anchor_headings < 0:
        sys.exit("--anchor-headings must be >= 0")
    estimate, truth, heading, vehicle, ids, names = load(args.folder)
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
    if args.anchor_headings > 0:
        print_anchor_headings(truth, heading, vehicle, ids, names, args.anchor_headings)
    i, j, offset = pairs_at_one_place(estimate, truth, vehicle, ids)
    if len(offset) == 0:
        print("pairs of two passes within 1 m: none")
        return
    p50, p90, p99 = np.percentile(offset, [50, 90, 99])
    print(f"pairs of two passes within 1 m: {len(offset)}, apart in the map beyond the truth "
          f"p50 {p50:.3f} p90 {p90:.3f} p99 {p99:.3f} m, over 1 m {100 * np.mean(offset > 1):.1f} %, "
          f"over 2 m {100 * np.mean(offset > 2):.1f} %")
    if args.store:
        rng = np.random.default_rng(1)
        shares = []
        for label, chosen in (("within 1 m", offset <= 1), ("over 1 m", offset > 1)):
            picked = np.flatnonzero(chosen)
            picked = rng.choice(picked, min(3000, len(picked)), replace=False)
            tied = tied_by_a_loop(args.store, names, vehicle, ids, i[picked], j[picked])
            shares.append(f"{label} {100 * tied.mean():.0f} % of {len(picked)}"
                          if len(picked) else f"{label}: none")
        print("pairs tied by a loop within 15 keyframes: " + ", ".join(shares))


if __name__ == "__main__":
    main()
