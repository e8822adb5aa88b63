#!/usr/bin/env bash
# The whole chain as the README's main job runs it, on a shorter fleet, inside a private
# network namespace: simulated 2-vehicle fleet -> litamin2-replay -> litamin2d -> aggregator
# -> export -> report. Passes when every odometry message equals the offline tool's, the
# aggregator stored every keyframe, and the second vehicle's keyframes, merged into the first
# one's frame by loop closure between the vehicles, are within MERGE_BOUND (0.5 m) of the
# ground truth there, without any alignment, and so is every pose the aggregator published live
# on rt/<vehicle>/map_odom in the map frame (MAP_ODOM_BOUND, 0.5 m; the second vehicle's
# odometry frame is not the map frame, so this checks the composition with its correction).
# Usage: fleet_chain.sh BUILD_DIR WORK_DIR SOURCE_DIR
set -euo pipefail
source "$(dirname "$0")/daemon_netns.sh"
DEMO_SKIP_BUILD=1 BUILD_DIR=$1 OUT=$2 FRAMES=${FRAMES:-120} DOMAIN=46 MERGE_BOUND=0.5 \
  MAP_ODOM_BOUND=0.5 \
  bash "$3/scripts/demo.sh"
# Passed: the simulated scans go (kept on failure for a look; CI has a disk of its own size).
rm -rf "$2/fleet"
