#!/usr/bin/env bash
# The fuzz harnesses of tests/fuzz under libFuzzer with ASan and UBSan (docs/security.md):
# configures ${FUZZ_BUILD_DIR:-build-fuzz} with clang and -DLITAMIN2_FUZZ=ON (only the harnesses
# and the libraries under them), builds it, and runs every harness for ${FUZZ_SECONDS:-20} s
# from a scratch copy of its seed corpus (ctest -L fuzz). Extra arguments go to ctest
# (e.g. -R map_patch). Installs clang and libclang-rt-14-dev if missing (install-deps.sh --fuzz).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh" --fuzz
build=${FUZZ_BUILD_DIR:-$root/build-fuzz}
seconds=${FUZZ_SECONDS:-20}
cxx=${FUZZ_CXX:-$(command -v clang++-14 || command -v clang++ || true)}
[ -n "$cxx" ] || { echo "fuzz.sh: clang++ not found (apt install clang libclang-rt-14-dev)" >&2; exit 1; }
launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S "$root" -B "$build" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" -DLITAMIN2_FUZZ=ON -DLITAMIN2_FUZZ_SECONDS="$seconds" \
  "${launcher[@]}" > /dev/null
cmake --build "$build" -j"${JOBS:-$(nproc)}" --target litamin2_fuzzers
cd "$build"
ctest --output-on-failure -L fuzz -j"${JOBS:-$(nproc)}" "$@"
