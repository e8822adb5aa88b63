#!/usr/bin/env bash
# litamin2-odometry on a folder of PCD scans with a per-point time field t: --deskew reads the
# times (all 0 here, the simulator's scans are taken at one pose, so the poses must equal the
# plain run's bit for bit while every frame counts as deskewed), and a truncated PCD at frame
# 12: without --skip-bad-frames the run fails naming the file; with it the file is logged and
# listed in stats.json, every frame still has a pose, and the trajectory ends where the intact
# run's does. frames.csv has a row per scan, the skipped one marked.
set -euo pipefail
tools=$1; work=$2
odo="$tools/odometry/litamin2-odometry"
rm -rf "$work"; mkdir -p "$work/pcd"
"$tools/sim/litamin2-sim" --builtin loop --frames 0:30 --output "$work/seq" 2>/dev/null
# velodyne/*.bin (x y z intensity float32) -> binary PCD with fields x y z intensity t.
python3 - "$work/seq/velodyne" "$work/pcd" <<'PY'
import os, struct, sys
src, dst = sys.argv[1], sys.argv[2]
for name in sorted(os.listdir(src)):
    data = open(os.path.join(src, name), 'rb').read()
    n = len(data) // 16
    out = bytearray()
    for i in range(n):
        out += data[16 * i:16 * i + 16] + struct.pack('<f', 0.0)
    header = ('# .PCD v0.7\nVERSION 0.7\nFIELDS x y z intensity t\nSIZE 4 4 4 4 4\n'
              'TYPE F F F F F\nCOUNT 1 1 1 1 1\nWIDTH %d\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\n'
              'POINTS %d\nDATA binary\n' % (n, n))
    open(os.path.join(dst, name.replace('.bin', '.pcd')), 'wb').write(header.encode() + out)
PY
test "$(ls "$work/pcd" | wc -l)" -eq 30
"$odo" -q -j 1 -o "$work/plain" "$work/pcd"
"$odo" -q -j 1 --deskew -o "$work/deskew" "$work/pcd" | tee "$work/deskew.log"
grep -q '"deskewed_frames": 30' "$work/deskew/stats.json" || { echo "FAIL: not every frame deskewed"; exit 1; }
cmp "$work/plain/poses_kitti.txt" "$work/deskew/poses_kitti.txt" \
  || { echo "FAIL: zero times changed the poses"; exit 1; }

# Frame 12 cut in the middle of its data.
bad="$work/pcd/000012.pcd"
truncate -s $(( $(stat -c %s "$bad") / 2 )) "$bad"
rc=0; "$odo" -q -j 1 -o "$work/strict" "$work/pcd" > "$work/strict.log" 2>&1 || rc=$?
[ "$rc" -eq 1 ] && grep -q "000012.pcd" "$work/strict.log" \
  || { echo "FAIL: a truncated scan without --skip-bad-frames: rc=$rc"; cat "$work/strict.log"; exit 1; }
"$odo" -q -j 1 --deskew --skip-bad-frames -o "$work/skip" "$work/pcd" 2> "$work/skip.err"
grep -q "skipping frame 12: .*000012.pcd" "$work/skip.err" \
  || { echo "FAIL: the bad file is not logged"; cat "$work/skip.err"; exit 1; }
python3 - "$work/skip/stats.json" <<'PY' || { echo "FAIL: stats.json does not list the skipped file"; exit 1; }
import json, sys
skipped = json.load(open(sys.argv[1]))["skipped_frames"]
assert len(skipped) == 1 and skipped[0]["frame"] == 12, skipped
assert skipped[0]["file"].endswith("000012.pcd") and skipped[0]["error"], skipped
PY
test "$(wc -l < "$work/skip/poses_kitti.txt")" -eq 30
# frames.csv: a header and one row per scan, the skipped one marked, the others registered
# (but the first) and their positions those of poses_kitti.txt.
python3 - "$work/skip/frames.csv" "$work/skip/poses_kitti.txt" <<'PY' || { echo "FAIL: frames.csv"; exit 1; }
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
poses = [list(map(float, l.split())) for l in open(sys.argv[2])]
assert len(rows) == 30, len(rows)
assert [r["index"] for r in rows] == [str(i) for i in range(30)]
assert rows[12]["status"] == "skipped" and rows[12]["file"] == "000012.pcd", rows[12]
assert rows[0]["status"] == "not_registered"
assert all(r["status"] == "registered" for i, r in enumerate(rows) if i not in (0, 12))
for i, r in enumerate(rows):
    if i == 12: continue
    p = poses[i]
    assert abs(float(r["x"]) - p[3]) < 1e-4 and abs(float(r["y"]) - p[7]) < 1e-4 and abs(float(r["z"]) - p[11]) < 1e-4, (i, r, p)
    assert 0.0 <= float(r["inlier_share"]) <= 1.0 and int(r["deskewed"]) == 1
PY
# The last pose (KITTI row: translation in columns 4, 8, 12) within 0.2 m of the intact run's.
d=$(paste -d' ' <(tail -1 "$work/plain/poses_kitti.txt") <(tail -1 "$work/skip/poses_kitti.txt") |
  awk '{ print sqrt(($4-$16)^2 + ($8-$20)^2 + ($12-$24)^2) }')
echo "last pose with frame 12 skipped: $d m from the intact run's"
awk -v d="$d" 'BEGIN { exit !(d < 0.2) }' || { echo "FAIL: the skipped frame lost the track"; exit 1; }
echo "1 passed, 0 failed"
