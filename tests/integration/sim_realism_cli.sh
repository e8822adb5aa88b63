#!/usr/bin/env bash
# litamin2-sim's realism options through the command line, on short VLP-16 runs of the built-in
# loop (issue 12):
# - without them no pcd/ and no source_frames.txt are written and no point is within 2 m;
# - --sweep-motion writes DIR/pcd/NNNNNN.pcd beside every velodyne/NNNNNN.bin: binary PCD with
#   fields x y z intensity t ring, the .bin's points, t in seconds from the sweep start in
#   [0, 0.1) in firing order;
# - --realism street drops frames: consecutive file names, source_frames.txt increasing with
#   gaps of at most --max-gap + 1, times.txt = 0.1 s x source frame, the ground truth of each file
#   that of its source frame (the mount tilt does not change it); every scan has self-hits
#   1-2 m behind and below the sensor (the roof rack; raw, so not smeared by the motion);
# - --self-hits none and --drop-frames 0 switch those parts off; bad values are rejected.
set -euo pipefail
tools=$(cd "$1" && pwd); work=$2
sim=$tools/sim/litamin2-sim
rm -rf "$work"; mkdir -p "$work"; work=$(cd "$work" && pwd); cd "$work"
run() { "$sim" --builtin loop --sensor vlp16 --threads 1 "$@" 2> "$work/last.log"; }

run --frames 0:20 --output plain
run --frames 0:6 --sweep-motion --output sweep
run --frames 0:20 --realism street --seed 3 --output street
run --frames 0:5 --realism street --self-hits none --drop-frames 0 --output bare

for bad in "--drop-frames 1.5" "--realism city" "--mount-tilt 1" "--max-gap 0"; do
  # shellcheck disable=SC2086
  if run --frames 0:3 $bad --output bad; then
    echo "accepted bad value: $bad"; exit 1
  fi
done

python3 - "$work" <<'PY'
import math, os, struct, sys
work = sys.argv[1]
fails = []
def check(ok, what):
    if not ok:
        fails.append(what)

def bin_points(path):
    data = open(path, "rb").read()
    assert len(data) % 16 == 0, path
    return [struct.unpack_from("<4f", data, 16 * i) for i in range(len(data) // 16)]

def read_pcd(path):
    data = open(path, "rb").read()
    end = data.index(b"DATA binary\n") + len(b"DATA binary\n")
    header = dict(l.split(" ", 1) for l in data[:end].decode().splitlines() if not l.startswith("#"))
    n = int(header["POINTS"])
    body = data[end:]
    stride = 22
    assert len(body) == n * stride, (path, len(body), n)
    return header, [struct.unpack_from("<5fH", body, stride * i) for i in range(n)]

def lines(path):
    return [l.split() for l in open(path) if l.strip()]

def near(points, r=2.0):
    return [p for p in points if math.sqrt(p[0] ** 2 + p[1] ** 2 + p[2] ** 2) < r]

# Plain: no realism output, nothing within 2 m.
plain = os.path.join(work, "plain")
check(not os.path.exists(os.path.join(plain, "pcd")), "plain run wrote pcd/")
check(not os.path.exists(os.path.join(plain, "source_frames.txt")), "plain run wrote source_frames.txt")
check(len(os.listdir(os.path.join(plain, "velodyne"))) == 20, "plain run: 20 scans")
check(all(not near(bin_points(os.path.join(plain, "velodyne", "%06d.bin" % i))) for i in (0, 10)),
      "plain run: points within 2 m")
plain_poses = [list(map(float, l)) for l in lines(os.path.join(plain, "poses.txt"))]

# Sweep motion: one PCD per .bin, with t in seconds from the sweep start.
sweep = os.path.join(work, "sweep")
bins = sorted(os.listdir(os.path.join(sweep, "velodyne")))
pcds = sorted(os.listdir(os.path.join(sweep, "pcd")))
check(len(bins) == 6 and [b[:-4] for b in bins] == [p[:-4] for p in pcds], "sweep: one pcd per bin")
check([float(l[0]) for l in lines(os.path.join(sweep, "times.txt"))] ==
      [float(l[0]) for l in lines(os.path.join(plain, "times.txt"))][:6], "sweep: times.txt")
for name in pcds:
    header, pts = read_pcd(os.path.join(sweep, "pcd", name))
    check(header["FIELDS"] == "x y z intensity t ring", name + ": FIELDS " + header["FIELDS"])
    check(header["TYPE"] == "F F F F F U" and header["SIZE"] == "4 4 4 4 4 2", name + ": TYPE/SIZE")
    xyz = bin_points(os.path.join(sweep, "velodyne", name[:-4] + ".bin"))
    check(len(xyz) == len(pts) > 10000, name + ": point count")
    check(all(abs(a[k] - b[k]) == 0.0 for a, b in zip(xyz, pts) for k in range(4)),
          name + ": pcd xyz/intensity differ from the .bin")
    t = [p[4] for p in pts]
    check(all(0.0 <= x < 0.1 for x in t), name + ": t outside [0, 0.1) s")
    check(all(a <= b for a, b in zip(t, t[1:])), name + ": t not in firing order")
    check(t[0] < 0.001 and t[-1] > 0.099, name + ": t does not span the sweep")
    check(all(p[5] < 16 for p in pts) and len({p[5] for p in pts}) == 16, name + ": rings")

# Street: dropped frames recorded, self-hits, pcd with time.
street = os.path.join(work, "street")
bins = sorted(os.listdir(os.path.join(street, "velodyne")))
n = len(bins)
check(bins == ["%06d.bin" % i for i in range(n)], "street: file names not consecutive")
check(5 <= n < 20, "street: %d of 20 frames kept" % n)
check(len(os.listdir(os.path.join(street, "pcd"))) == n, "street: pcd count")
src = [int(l[0]) for l in lines(os.path.join(street, "source_frames.txt"))]
times = [float(l[0]) for l in lines(os.path.join(street, "times.txt"))]
poses = [list(map(float, l)) for l in lines(os.path.join(street, "poses.txt"))]
check(len(src) == len(times) == len(poses) == n, "street: source_frames/times/poses lengths")
check(src[0] == 0 and all(1 <= b - a <= 4 for a, b in zip(src, src[1:])), "street: gaps %s" % src)
check(any(b - a > 1 for a, b in zip(src, src[1:])), "street: no frame dropped")
check(all(abs(t - 0.1 * s) < 1e-6 for t, s in zip(times, src)), "street: times != 0.1 x source")
check(all(max(abs(a - b) for a, b in zip(poses[k], plain_poses[s])) < 1e-5
          for k, s in enumerate(src)), "street: ground truth is not the source frame's")
for k in range(n):
    hits = near(bin_points(os.path.join(street, "velodyne", bins[k])))
    ranges = [math.sqrt(p[0] ** 2 + p[1] ** 2 + p[2] ** 2) for p in hits]
    check(len(hits) > 500, "street %d: %d points within 2 m" % (k, len(hits)))
    check(all(r >= 1.0 for r in ranges), "street %d: points nearer than 1 m" % k)
    check(all(p[0] < 0 and p[2] < 0 for p in hits), "street %d: self-hits not behind and below" % k)

# Parts switched off.
bare = os.path.join(work, "bare")
check(not os.path.exists(os.path.join(bare, "source_frames.txt")), "bare: source_frames.txt")
check(len(os.listdir(os.path.join(bare, "velodyne"))) == 5, "bare: 5 scans")
check(len(os.listdir(os.path.join(bare, "pcd"))) == 5, "bare: sweep motion stays on")
check(not near(bin_points(os.path.join(bare, "velodyne", "000002.bin"))), "bare: self-hits")

for f in fails:
    print("FAIL:", f)
if fails:
    sys.exit(1)
print("street: %d of 20 frames kept (source frames %s)" % (n, src))
PY
echo "1 passed, 0 failed"
