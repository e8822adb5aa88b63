#!/usr/bin/env bash
# Bad input to litamin2-odometry: one "litamin2-odometry: error:" line naming what is wrong, exit
# status 2 for a usage error (option, configuration file) and 1 for bad input data, never a crash.
set -uo pipefail
tools=$1; work=$2
odo="$tools/odometry/litamin2-odometry"
rm -rf "$work"; mkdir -p "$work/seq"
failures=0
expect() {  # expect NAME RC PATTERN -- command...
  local name=$1 want=$2 pattern=$3; shift 4
  local out rc
  out=$("$@" 2>&1); rc=$?
  if [ "$rc" -ne "$want" ] || ! grep -q -- "^litamin2-odometry: error: .*$pattern" <<<"$out"; then
    echo "FAIL $name: rc=$rc, output: $out"; failures=$((failures + 1))
  else
    echo "ok   $name"
  fi
}
expect unknown-mode 2 "mode" -- "$odo" --mode gicp -o "$work/out" "$work/seq"
expect missing-input 1 "no-such-folder" -- "$odo" -o "$work/out" "$work/no-such-folder"
expect empty-folder 1 "seq" -- "$odo" -o "$work/out" "$work/seq"
head -c 1001 /dev/urandom > "$work/seq/000000.bin"
expect corrupt-scan 1 "000000.bin" -- "$odo" -o "$work/out" "$work/seq"
printf 'registration: {sigma_icp: -1}\n' > "$work/bad.yaml"
expect bad-config-value 2 "registration.sigma_icp: -1" -- "$odo" -c "$work/bad.yaml" -o "$work/out" "$work/seq"
printf 'registration: {sigma_icpp: 1}\n' > "$work/typo.yaml"
expect unknown-config-key 2 "registration.sigma_icpp: unknown key" -- "$odo" -c "$work/typo.yaml" -o "$work/out" "$work/seq"
expect missing-config 2 "nope.yaml" -- "$odo" -c "$work/nope.yaml" -o "$work/out" "$work/seq"
printf 'verification: {min_fitness: 2}\n' > "$work/mapper.yaml"
expect bad-mapper-value 2 "verification.min_fitness: 2 is out of range" -- \
  "$odo" --loop-closure --mapper-config "$work/mapper.yaml" -o "$work/out" "$work/seq"
expect missing-mapper-config 2 "nope.yaml" -- \
  "$odo" --loop-closure --mapper-config "$work/nope.yaml" -o "$work/out" "$work/seq"
# Stamps (times.txt) that do not increase: the tracker predicts with the time between scans.
mkdir -p "$work/stamps/velodyne"
head -c 1600 /dev/zero > "$work/stamps/velodyne/000000.bin"
cp "$work/stamps/velodyne/000000.bin" "$work/stamps/velodyne/000001.bin"
printf '0.5\n0.5\n' > "$work/stamps/times.txt"
expect repeated-stamp 1 "stamp 500000000 ns is not after the previous" -- "$odo" -o "$work/out" "$work/stamps"
"$odo" --help | grep -q -- "--voxel-size" || { echo "FAIL help"; failures=$((failures + 1)); }
"$odo" --help | grep -q -- "--loop-closure" || { echo "FAIL help"; failures=$((failures + 1)); }
echo "$((11 - failures)) passed, $failures failed"
[ "$failures" -eq 0 ]
