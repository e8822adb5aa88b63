#!/usr/bin/env bash
# A shared build (-DBUILD_SHARED_LIBS=ON, tests and benchmarks off) installs every project
# library beside its tools and the installed tools run from the install tree alone: each
# prints --help, resolves every litamin2 library from <prefix>/lib (RPATH $ORIGIN/../lib), and
# the installed daemon and aggregator accept their installed default configs. Also checks that
# -DLITAMIN2_BUILD_TOOLS=OFF still defines every library (the daemon's and the aggregator's
# included).
# Usage: deploy_shared_install.sh SOURCE_DIR WORK_DIR. Takes an unoptimised full build's time
# (~3-4 min on 2 idle cores without a compiler cache).
set -uo pipefail
src=$1; work=$2
rm -rf "$work"; mkdir -p "$work"
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }

# 1. Libraries without tools: every library target is still defined.
if cmake -S "$src" -B "$work/no-tools" -DLITAMIN2_BUILD_TOOLS=OFF -DLITAMIN2_BUILD_TESTS=OFF \
    -DLITAMIN2_BUILD_BENCH=OFF > "$work/no-tools.log" 2>&1; then
  targets=$(cmake --build "$work/no-tools" --target help 2>/dev/null)
  for lib in core io eval service config mapping store sim dds_types dds daemon daemon_dds \
      aggregator aggregator_dds; do
    grep -q "litamin2_$lib\$" <<<"$targets" || fail "no litamin2_$lib target with LITAMIN2_BUILD_TOOLS=OFF"
  done
  echo "ok   LITAMIN2_BUILD_TOOLS=OFF defines every library"
else
  fail "configure with LITAMIN2_BUILD_TOOLS=OFF: $(tail -5 "$work/no-tools.log")"
fi

# 2. A shared build, installed with DESTDIR and run from there.
build="$work/shared"; dest="$work/root"; prefix=/opt/litamin2
# Release layout and flags as installed, but compiled without optimisation (-O0): what this test
# checks is linking, installing and starting, and -O0 halves the build's time in the suite.
if ! cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O0 -DNDEBUG" \
    -DBUILD_SHARED_LIBS=ON -DLITAMIN2_BUILD_TESTS=OFF -DLITAMIN2_BUILD_BENCH=OFF \
    > "$work/configure.log" 2>&1; then
  fail "configure: $(tail -5 "$work/configure.log")"; exit 1
fi
if ! cmake --build "$build" -j"$(nproc)" > "$work/build.log" 2>&1; then
  fail "build: $(grep -m3 -B2 'error' "$work/build.log")"; exit 1
fi
if ! DESTDIR="$dest" cmake --install "$build" --prefix "$prefix" > "$work/install.log" 2>&1; then
  fail "install: $(tail -5 "$work/install.log")"; exit 1
fi
built_libs=$(find "$build" -name 'liblitamin2_*.so' -printf '%f\n' | sort -u)
[ -n "$built_libs" ] || fail "the shared build made no liblitamin2_*.so"
for lib in $built_libs; do
  [ -e "$dest$prefix/lib/$lib" ] || fail "$lib built but not installed in $prefix/lib"
done
echo "ok   $(wc -w <<<"$built_libs") shared libraries installed in $prefix/lib"
# The build tree must not be what the tools load: move it away while they run.
mv "$build" "$build.away"
libdir=$(realpath "$dest$prefix/lib")
before_tools=$failures
for tool in "$dest$prefix"/bin/*; do
  name=$(basename "$tool")
  resolved=$(env -u LD_LIBRARY_PATH ldd "$tool" 2>&1)
  missing=$(grep -E 'not found' <<<"$resolved" || true)
  [ -z "$missing" ] || fail "$name: $missing"
  while read -r lib path; do
    [ -n "$path" ] || continue
    [ "$(dirname "$(realpath "$path")")" = "$libdir" ] || fail "$name loads $lib from $path"
  done < <(awk '/liblitamin2_/ && $3 ~ /^\// {print $1, $3}' <<<"$resolved")
  env -u LD_LIBRARY_PATH "$tool" --help > "$work/$name.help" 2>&1 || fail "$name --help exited $?"
done
etc="$dest$prefix/etc/litamin2"
if [ -x "$dest$prefix/bin/litamin2d" ]; then
  out=$("$dest$prefix/bin/litamin2d" --check-config --config "$etc/litamin2d.yaml" 2>&1) ||
    fail "installed litamin2d --check-config: $out"
fi
if [ -x "$dest$prefix/bin/litamin2-aggregator" ]; then
  out=$("$dest$prefix/bin/litamin2-aggregator" --check-config --config "$etc/litamin2-aggregator.yaml" 2>&1) ||
    fail "installed litamin2-aggregator --check-config: $out"
fi
mv "$build.away" "$build"
[ "$failures" -eq "$before_tools" ] &&
  echo "ok   $(ls "$dest$prefix/bin" | wc -l) installed tools run from $prefix/bin"
[ "$failures" -eq 0 ] && echo "deploy_shared_install: all checks passed" ||
  echo "deploy_shared_install: $failures failure(s)"
[ "$failures" -eq 0 ]
