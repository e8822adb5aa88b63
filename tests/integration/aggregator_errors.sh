#!/usr/bin/env bash
# litamin2-aggregator's refusals: a corrupt store (the service and export exit non-zero with a
# message naming the file, and the file is not modified), bad configurations, and the
# informational options. Usage: aggregator_errors.sh BUILD_DIR WORK_DIR SOURCE_DIR
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
build=$1
work=$2
source_dir=$3
aggregator=$build/tools/aggregator/litamin2-aggregator
rm -rf "$work"
mkdir -p "$work"
cd "$work"

expect_fail() {  # expect_fail STATUS PATTERN COMMAND...: exit status and message
  local want=$1 pattern=$2
  shift 2
  local status=0
  "$@" > out.log 2>&1 || status=$?
  if [ "$status" -ne "$want" ] || ! grep -q -- "$pattern" out.log; then
    echo "FAIL: $* exited $status (want $want), output:"; cat out.log; exit 1
  fi
  echo "ok ($status): $(grep -m1 -- "$pattern" out.log)"
}

echo "== informational options"
"$aggregator" --help | grep -q -- "--check-config"
"$aggregator" export --help | grep -q -- "--trajectories"
"$aggregator" --version | grep -q "litamin2-aggregator"
"$aggregator" --check-config --config "$source_dir/config/litamin2-aggregator.yaml"

echo "== bad configurations"
expect_fail 2 "missing.yaml: cannot open" "$aggregator" --config missing.yaml
printf 'dds: {domain: 999}\n' > c1.yaml
expect_fail 2 "c1.yaml: dds.domain: 999 is out of range" "$aggregator" --config c1.yaml
printf 'mapper: {place_recognition: {rings: x}}\n' > c2.yaml
expect_fail 2 "mapper.place_recognition.rings: cannot read 'x'" "$aggregator" --config c2.yaml
printf 'store: {path: a.db, colour: red}\n' > c3.yaml
expect_fail 2 "store.colour: unknown key" "$aggregator" --check-config --config c3.yaml
printf 'dds: [\n' > c4.yaml
expect_fail 2 "c4.yaml: not valid YAML" "$aggregator" --config c4.yaml
expect_fail 2 "^litamin2-aggregator: error: export: give --map and/or --trajectories" \
  "$aggregator" export --store x.db
# A map name that is neither .ply nor .pcd is refused (exit 2) before the store is opened.
expect_fail 2 "^litamin2-aggregator: error: export: --map m.txt: unsupported map format" \
  "$aggregator" export --store x.db --map m.txt
[ ! -e m.txt ] && [ ! -e x.db ] || { echo "FAIL: export --map m.txt wrote a file"; exit 1; }

echo "== corrupt stores are refused and left untouched"
head -c 8192 /dev/urandom > random.db
printf 'SQLite format 3\0' > truncated.db
head -c 5000 /dev/urandom >> truncated.db
for db in random.db truncated.db; do
  sum=$(md5sum < "$db")
  printf 'dds: {domain: 43}\nstore: {path: %s}\n' "$db" > corrupt.yaml
  expect_fail 1 "cannot use the store: $db" "$aggregator" --config corrupt.yaml
  expect_fail 1 "cannot read the store: $db" "$aggregator" export --store "$db" --map m.ply
  [ "$sum" = "$(md5sum < "$db")" ] || { echo "FAIL: $db was modified"; exit 1; }
  [ ! -e "$db-wal" ] || { echo "FAIL: $db-wal was created"; exit 1; }
done
expect_fail 1 "missing.db" "$aggregator" export --store missing.db --map m.ply
[ ! -e missing.db ] || { echo "FAIL: export created missing.db"; exit 1; }
echo "all refusals as expected"
