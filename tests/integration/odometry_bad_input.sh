#!/usr/bin/env bash
# Bad input to litamin2-odometry: a clear message naming what is wrong and exit status 1, never
# a crash.
set -uo pipefail
tools=$1; work=$2
odo="$tools/odometry/litamin2-odometry"
rm -rf "$work"; mkdir -p "$work/seq"
failures=0
expect() {  # expect NAME PATTERN -- command...
  local name=$1 pattern=$2; shift 3
  local out rc
  out=$("$@" 2>&1); rc=$?
  if [ "$rc" -ne 1 ] || ! grep -q -- "$pattern" <<<"$out"; then
    echo "FAIL $name: rc=$rc, output: $out"; failures=$((failures + 1))
  else
    echo "ok   $name"
  fi
}
expect unknown-mode "mode" -- "$odo" --mode gicp -o "$work/out" "$work/seq"
expect missing-input "no-such-folder" -- "$odo" -o "$work/out" "$work/no-such-folder"
expect empty-folder "seq" -- "$odo" -o "$work/out" "$work/seq"
head -c 1001 /dev/urandom > "$work/seq/000000.bin"
expect corrupt-scan "000000.bin" -- "$odo" -o "$work/out" "$work/seq"
printf 'registration: {sigma_icp: -1}\n' > "$work/bad.yaml"
expect bad-config-value "registration.sigma_icp: -1" -- "$odo" -c "$work/bad.yaml" -o "$work/out" "$work/seq"
printf 'registration: {sigma_icpp: 1}\n' > "$work/typo.yaml"
expect unknown-config-key "registration.sigma_icpp: unknown key" -- "$odo" -c "$work/typo.yaml" -o "$work/out" "$work/seq"
expect missing-config "nope.yaml" -- "$odo" -c "$work/nope.yaml" -o "$work/out" "$work/seq"
printf 'verification: {min_fitness: 2}\n' > "$work/mapper.yaml"
expect bad-mapper-value "verification.min_fitness: 2 is out of range" -- \
  "$odo" --loop-closure --mapper-config "$work/mapper.yaml" -o "$work/out" "$work/seq"
expect missing-mapper-config "nope.yaml" -- \
  "$odo" --loop-closure --mapper-config "$work/nope.yaml" -o "$work/out" "$work/seq"
"$odo" --help | grep -q -- "--voxel-size" || { echo "FAIL help"; failures=$((failures + 1)); }
"$odo" --help | grep -q -- "--loop-closure" || { echo "FAIL help"; failures=$((failures + 1)); }
echo "$((10 - failures)) passed, $failures failed"
[ "$failures" -eq 0 ]
