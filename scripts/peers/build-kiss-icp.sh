#!/usr/bin/env bash
# Builds KISS-ICP (PRBonn/kiss-icp, its C++ core) from a source folder you provide, and
# scripts/peers/kiss_icp_runner against it: a benchmark-only peer for side-by-side odometry runs
# (scripts/peers/side-by-side.sh, docs/accuracy.md). Nothing of KISS-ICP enters litamin2's tree
# or build; BUILD should be outside the repository.
#
# Usage: scripts/peers/build-kiss-icp.sh KISS_ICP_SRC BUILD [SOPHUS_SRC]
#   KISS_ICP_SRC  a checkout of PRBonn/kiss-icp (e.g. tag v1.2.3); its cpp/kiss_icp is built
#   BUILD         build folder; the runner ends up at BUILD/kiss_icp_runner
#   SOPHUS_SRC    a checkout of strasdat/Sophus (e.g. tag 1.22.10). Debian 12 has no Sophus
#                 package and KISS-ICP would otherwise download it; it is installed header-only
#                 into BUILD/sophus-prefix. Not needed when Sophus is already findable by CMake.
# Needs (Debian): cmake g++ libeigen3-dev libtbb-dev robin-map-dev libfmt-dev.
# Example, from mirrors of the two repositories:
#   git -C MIRROR/kiss-icp worktree add /tmp/kiss-icp-src v1.2.3   (or git archive | tar -x)
#   scripts/peers/build-kiss-icp.sh /tmp/kiss-icp-src /tmp/kiss-icp-build /tmp/sophus-src
set -euo pipefail
usage() { sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; }
case "${1:-}" in -h | --help) usage; exit 0 ;; esac
[ $# -ge 2 ] && [ $# -le 3 ] || { usage >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$1" && pwd)
mkdir -p "$2"
build=$(cd "$2" && pwd)
[ -f "$src/cpp/kiss_icp/CMakeLists.txt" ] || { echo "$src: no cpp/kiss_icp/CMakeLists.txt (not a kiss-icp checkout)" >&2; exit 1; }
prefix_args=()
if [ $# -eq 3 ]; then
  sophus=$(cd "$3" && pwd)
  [ -f "$sophus/sophus/se3.hpp" ] || { echo "$sophus: no sophus/se3.hpp (not a Sophus checkout)" >&2; exit 1; }
  cmake -S "$sophus" -B "$build/sophus-build" -DCMAKE_BUILD_TYPE=Release \
    -DBUILD_SOPHUS_TESTS=OFF -DBUILD_SOPHUS_EXAMPLES=OFF -DBUILD_PYTHON_BINDINGS=OFF \
    -DSOPHUS_USE_BASIC_LOGGING=ON -DCMAKE_INSTALL_PREFIX="$build/sophus-prefix" >/dev/null
  cmake --install "$build/sophus-build" >/dev/null
  prefix_args=(-DCMAKE_PREFIX_PATH="$build/sophus-prefix")
fi
cmake -S "$here/kiss_icp_runner" -B "$build/runner" -DCMAKE_BUILD_TYPE=Release \
  -DKISS_ICP_SOURCE_DIR="$src/cpp/kiss_icp" -DUSE_CCACHE=OFF "${prefix_args[@]}"
cmake --build "$build/runner" -j"${JOBS:-2}"
cp "$build/runner/kiss_icp_runner" "$build/kiss_icp_runner"
version=$(sed -n 's/^project(kiss_icp_cpp VERSION \([0-9.]*\).*/\1/p' "$src/cpp/kiss_icp/CMakeLists.txt")
echo "kiss_icp_runner: $build/kiss_icp_runner (KISS-ICP ${version:-of unknown version} from $src)"
