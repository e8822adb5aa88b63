#!/usr/bin/python3
"""A reference for frame-to-frame motion that needs no ground truth and no odometry: each
consecutive pair of scans registered on its own, scan to scan.

  pairwise_reference.py make SCANS OUT.txt [--first A] [--last B]
  pairwise_reference.py compare REF.txt NAME=POSES [NAME=POSES ...] [--per-frame]

make: for each file i > A of SCANS (a folder of .pcd or KITTI .bin scans, sorted by name; or a
KITTI sequence folder with velodyne/), the motion of scan i in the frame of scan i-1 is found
by a correlative x/y/yaw search over a 2D occupancy image of the scans' points above the
ground (+-8 m, +-30 deg, 0.2 m and 1 deg steps, by FFT cross-correlation), refined by
point-to-plane ICP in 3D (robust Cauchy weights, 0.1 m). Each line of OUT.txt:
  i dx dy dz yaw_deg fitness_median_m inlier_share
fitness_median_m is the median distance from scan i's points, moved by the motion, to their
nearest point of scan i-1 (capped at 2 m); inlier_share the share of them within 0.2 m. A pair
is "registrable" when fitness_median_m < 0.25 and inlier_share > 0.4: the two scans agree
under that motion. Pairs that are not have no motion within the window under which the scans
agree (a break in the input: frames missing, a turn) and tell nothing.

compare: for each path (KITTI 3x4 rows, one per file, e.g. litamin2-odometry's
poses_kitti.txt), the planar translation (m) and yaw (deg) differences of its consecutive
motions from the reference on the registrable pairs: median, 95th percentile and the count of
pairs more than 0.5 m off. --per-frame prints every pair.

The reference is an estimate, not ground truth: repeated structure (a row of parked cars) can
alias by its period. It needs python3-numpy and python3-scipy (Debian). docs/accuracy.md,
"Breaks that cannot be registered".
"""
import glob
import os
import sys

USAGE = __doc__.split("\n\n")[1]


def fail(message):
    sys.stderr.write("pairwise_reference.py: %s\n" % message)
    sys.exit(2)


try:
    import numpy as np
    from scipy.ndimage import gaussian_filter
    from scipy.spatial import cKDTree
    from scipy.spatial.transform import Rotation
except ImportError as e:  # pragma: no cover
    fail("%s (install python3-numpy and python3-scipy)" % e)

GRID_RES, GRID_CELLS = 0.2, 512
MAX_SHIFT_M, MAX_YAW_DEG = 8.0, 30
REGISTRABLE_MEDIAN_M, REGISTRABLE_INLIERS = 0.25, 0.4


def read_pcd(path):
    with open(path, "rb") as f:
        header = {}
        while True:
            line = f.readline()
            if not line:
                raise ValueError("%s: no DATA line" % path)
            words = line.decode("ascii", "replace").split()
            if not words or words[0].startswith("#"):
                continue
            header[words[0].upper()] = words[1:]
            if words[0].upper() == "DATA":
                break
        fields = header.get("FIELDS", [])
        if fields[:3] != ["x", "y", "z"]:
            raise ValueError("%s: the first fields are not x y z" % path)
        count = int(header.get("POINTS", ["0"])[0])
        kind = header["DATA"][0]
        if kind == "ascii":
            data = np.loadtxt(f, dtype=np.float64, ndmin=2)
            return data[:, :3]
        if kind == "binary":
            sizes = [int(s) for s in header["SIZE"]]
            types = header["TYPE"]
            counts = [int(c) for c in header.get("COUNT", ["1"] * len(fields))]
            dtype = np.dtype([(n, {"F": "<f", "I": "<i", "U": "<u"}[t] + str(s), (c,))
                              for n, s, t, c in zip(fields, sizes, types, counts)])
            rec = np.frombuffer(f.read(dtype.itemsize * count), dtype=dtype, count=count)
            return np.stack([rec[a][:, 0] for a in "xyz"], 1).astype(np.float64)
        raise ValueError("%s: DATA %s is not read here (ascii or binary)" % (path, kind))


def read_scan(path):
    if path.endswith(".bin"):
        return np.fromfile(path, dtype=np.float32).reshape(-1, 4)[:, :3].astype(np.float64)
    return read_pcd(path)


def scan_files(folder):
    if os.path.isdir(os.path.join(folder, "velodyne")):
        folder = os.path.join(folder, "velodyne")
    files = sorted(glob.glob(os.path.join(folder, "*.pcd")) + glob.glob(os.path.join(folder, "*.bin")))
    if not files:
        fail("%s: no .pcd or .bin scans" % folder)
    return files


def in_range(points, z_min):
    r = np.linalg.norm(points[:, :2], axis=1)
    keep = (r > 3.0) & (r < 40.0) & (points[:, 2] > z_min) & np.isfinite(points).all(1)
    return points[keep]


def rot_z(yaw):
    c, s = np.cos(yaw), np.sin(yaw)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def occupancy(points):
    grid = np.zeros((GRID_CELLS, GRID_CELLS))
    ix = np.floor(points[:, 0] / GRID_RES).astype(int) + GRID_CELLS // 2
    iy = np.floor(points[:, 1] / GRID_RES).astype(int) + GRID_CELLS // 2
    keep = (ix >= 0) & (ix < GRID_CELLS) & (iy >= 0) & (iy < GRID_CELLS)
    grid[ix[keep], iy[keep]] = 1.0
    return grid


def correlative_start(previous, current):
    """Best x, y, yaw of `current` in `previous`'s frame by 2D cross-correlation."""
    spectrum = np.fft.fft2(gaussian_filter(occupancy(previous), 1.5))
    k = int(MAX_SHIFT_M / GRID_RES)
    best = (-1.0, np.eye(4))
    for yaw_deg in range(-MAX_YAW_DEG, MAX_YAW_DEG + 1):
        turned = current @ rot_z(np.radians(yaw_deg)).T
        c = np.real(np.fft.ifft2(spectrum * np.conj(np.fft.fft2(occupancy(turned)))))
        c = np.roll(np.roll(c, k, 0), k, 1)[: 2 * k + 1, : 2 * k + 1]
        i, j = np.unravel_index(np.argmax(c), c.shape)
        if c[i, j] > best[0]:
            t = np.eye(4)
            t[:3, :3] = rot_z(np.radians(yaw_deg))
            t[:3, 3] = [(i - k) * GRID_RES, (j - k) * GRID_RES, 0.0]
            best = (c[i, j], t)
    return best[1]


def point_to_plane(previous, current, start, iterations=30):
    tree = cKDTree(previous)
    _, neighbours = tree.query(previous, k=8)
    centred = previous[neighbours] - previous[neighbours].mean(1, keepdims=True)
    normals = np.linalg.eigh(np.einsum("nki,nkj->nij", centred, centred))[1][:, :, 0]
    t = start.copy()
    for _ in range(iterations):
        moved = current @ t[:3, :3].T + t[:3, 3]
        d, k = tree.query(moved, distance_upper_bound=1.0)
        ok = np.isfinite(d)
        p, q, n = moved[ok], previous[k[ok]], normals[k[ok]]
        r = np.sum((p - q) * n, 1)
        jac = np.hstack([np.cross(p, n), n])
        w = 1.0 / (1.0 + (r / 0.1) ** 2)
        step = -np.linalg.solve(jac.T @ (jac * w[:, None]) + 1e-6 * np.eye(6), jac.T @ (w * r))
        update = np.eye(4)
        update[:3, :3] = Rotation.from_rotvec(step[:3]).as_matrix()
        update[:3, 3] = step[3:]
        t = update @ t
        if np.linalg.norm(step) < 1e-5:
            break
    moved = current @ t[:3, :3].T + t[:3, 3]
    d = np.minimum(tree.query(moved, distance_upper_bound=2.0)[0], 2.0)
    return t, float(np.median(d)), float(np.mean(d < 0.2))


def make(args):
    if len(args) < 2:
        fail("usage: " + USAGE)
    folder, out = args[0], args[1]
    first, last = 0, None
    rest = args[2:]
    while rest:
        if rest[0] == "--first" and len(rest) > 1:
            first = int(rest[1])
        elif rest[0] == "--last" and len(rest) > 1:
            last = int(rest[1])
        else:
            fail("unknown option %s" % rest[0])
        rest = rest[2:]
    files = scan_files(folder)
    last = len(files) if last is None else min(last, len(files))
    previous = read_scan(files[first])
    with open(out, "w") as f:
        for i in range(first + 1, last):
            current = read_scan(files[i])
            start = correlative_start(in_range(previous, -0.5), in_range(current, -0.5))
            t, median, inliers = point_to_plane(in_range(previous, -1.0)[::2], in_range(current, -1.0)[::4], start)
            yaw = np.degrees(np.arctan2(t[1, 0], t[0, 0]))
            f.write("%d %.4f %.4f %.4f %.3f %.4f %.4f\n" % (i, t[0, 3], t[1, 3], t[2, 3], yaw, median, inliers))
            f.flush()
            if (i - first) % 25 == 0:
                sys.stderr.write("pairwise_reference.py: %d of %d pairs\n" % (i - first, last - first - 1))
            previous = current


def relative_motions(path):
    rows = np.loadtxt(path, ndmin=2)
    if rows.shape[1] != 12:
        fail("%s: not KITTI 3x4 rows" % path)
    poses = rows.reshape(-1, 3, 4)
    out = {}
    for i in range(1, len(poses)):
        a = np.vstack([poses[i - 1], [0, 0, 0, 1]])
        b = np.vstack([poses[i], [0, 0, 0, 1]])
        out[i] = np.linalg.inv(a) @ b
    return out


def compare(args):
    per_frame = "--per-frame" in args
    args = [a for a in args if a != "--per-frame"]
    if len(args) < 2 or any("=" not in a for a in args[1:]):
        fail("usage: " + USAGE)
    reference = {}
    for line in open(args[0]):
        w = line.split()
        if len(w) == 7:
            reference[int(w[0])] = [float(x) for x in w[1:]]
    good = sorted(i for i, r in reference.items()
                  if r[4] < REGISTRABLE_MEDIAN_M and r[5] > REGISTRABLE_INLIERS)
    print("registrable pairs: %d of %d" % (len(good), len(reference)))
    paths = [(name, relative_motions(p)) for name, p in (a.split("=", 1) for a in args[1:])]
    for name, motions in paths:
        missing = [i for i in good if i not in motions]
        if missing:
            fail("%s: no pose for file %d" % (name, missing[0]))
        dt = np.array([np.hypot(motions[i][0, 3] - reference[i][0], motions[i][1, 3] - reference[i][1]) for i in good])
        dr = np.array([abs((np.degrees(np.arctan2(motions[i][1, 0], motions[i][0, 0])) - reference[i][3] + 180) % 360 - 180) for i in good])
        print("%s: translation m p50 %.3f p95 %.3f, yaw deg p50 %.2f p95 %.2f, pairs > 0.5 m off: %d of %d"
              % (name, np.median(dt), np.percentile(dt, 95), np.median(dr), np.percentile(dr, 95), int(np.sum(dt > 0.5)), len(good)))
    if per_frame:
        for i in sorted(reference):
            r = reference[i]
            line = "%4d %s ref %7.2f %6.2f %6.1f" % (i, "R" if i in good else "-", r[0], r[1], r[3])
            for name, motions in paths:
                m = motions.get(i)
                if m is not None:
                    line += " | %s %7.2f %6.2f %6.1f" % (name, m[0, 3], m[1, 3], np.degrees(np.arctan2(m[1, 0], m[0, 0])))
            print(line)


def main():
    if len(sys.argv) < 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return
    command, args = sys.argv[1], sys.argv[2:]
    if command == "make":
        make(args)
    elif command == "compare":
        compare(args)
    else:
        fail("unknown command %s; usage: %s" % (command, USAGE))


if __name__ == "__main__":
    main()
