# litamin2-aggregator end to end over real DDS, inside a private network namespace (unshare -n,
# only lo up) and with the loopback-only transport profile.
#  - integration_aggregator_restart: keyframes of a simulated loop (the core Tracker, offline)
#    published as map patches for two streams by aggregator_probe; one aggregator runs
#    uninterrupted, another is killed with SIGKILL mid-ingest, restarted and fed the rest
#    reversed and duplicated; both stores' exports (map PLY, KITTI/TUM trajectories) must be
#    byte-identical.
#  - integration_aggregator_fleet_bench: litamin2-fleet-bench at small sizes, as a
#    correctness test (loops, ATE, restart from the tables of a 20k-keyframe store).
#  - integration_aggregator_fleet_bench_stop: the bench stopped by --max-wall-s and by SIGTERM
#    finishes as at the end and writes a valid summary marked stopped_early.
#  - integration_map_tiles: the map tiles on rt/litamin2/map_tiles and litamin2-map-tiles
#    (content-filtered box, early and late-joining clients, revisions across a restart).
#  - integration_aggregator_standby: two aggregators in hot standby (standby.strength 2 and 1)
#    on the same patches, the stronger killed with SIGKILL mid-ingest: an exclusive reader of the
#    poses switches to the other within the lease; the two maps compared.
#  - integration_aggregator_errors: corrupt store (aggregator and export exit non-zero naming
#    the file, bytes unchanged), bad configurations, --help/--version/--check-config.
if(TARGET litamin2-aggregator)
  add_executable(aggregator_probe ${CMAKE_CURRENT_LIST_DIR}/aggregator_probe/main.cpp)
  target_include_directories(aggregator_probe PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_link_libraries(aggregator_probe PRIVATE litamin2_dds litamin2_core litamin2_io
    litamin2_mapping CLI11::CLI11)
  # Records the aggregator's map-frame odometry (the fleet chain test, scripts/demo.sh).
  add_executable(map_odom_probe ${CMAKE_CURRENT_LIST_DIR}/map_odom_probe/main.cpp)
  target_include_directories(map_odom_probe PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_link_libraries(map_odom_probe PRIVATE litamin2_dds CLI11::CLI11)

  add_test(NAME integration_aggregator_errors
    COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/aggregator_errors.sh ${CMAKE_BINARY_DIR}
      ${CMAKE_CURRENT_BINARY_DIR}/aggregator_errors ${CMAKE_SOURCE_DIR})
  set_tests_properties(integration_aggregator_errors PROPERTIES TIMEOUT 120 RUN_SERIAL TRUE)

  if(TARGET litamin2-map-tiles)
    add_test(NAME integration_map_tiles
      COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/map_tiles.sh ${CMAKE_BINARY_DIR}
        ${CMAKE_CURRENT_BINARY_DIR}/map_tiles)
    set_tests_properties(integration_map_tiles PROPERTIES TIMEOUT 180 RUN_SERIAL TRUE)
  endif()
  if(TARGET litamin2-fleet-bench)
    add_test(NAME integration_aggregator_fleet_bench
      COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/aggregator_fleet_bench.sh ${CMAKE_BINARY_DIR}
        ${CMAKE_CURRENT_BINARY_DIR}/aggregator_fleet_bench)
    set_tests_properties(integration_aggregator_fleet_bench PROPERTIES TIMEOUT 600)
    add_test(NAME integration_aggregator_fleet_bench_stop
      COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/aggregator_fleet_bench_stop.sh ${CMAKE_BINARY_DIR}
        ${CMAKE_CURRENT_BINARY_DIR}/aggregator_fleet_bench_stop)
    set_tests_properties(integration_aggregator_fleet_bench_stop PROPERTIES TIMEOUT 300)
  endif()
  if(TARGET litamin2-sim)
    add_test(NAME integration_aggregator_restart
      COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/aggregator_restart.sh ${CMAKE_BINARY_DIR}
        ${CMAKE_CURRENT_BINARY_DIR}/aggregator_restart ${CMAKE_SOURCE_DIR})
    set_tests_properties(integration_aggregator_restart PROPERTIES TIMEOUT 600 RUN_SERIAL TRUE)
    add_test(NAME integration_aggregator_standby
      COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/aggregator_standby.sh ${CMAKE_BINARY_DIR}
        ${CMAKE_CURRENT_BINARY_DIR}/aggregator_standby)
    set_tests_properties(integration_aggregator_standby PROPERTIES TIMEOUT 600 RUN_SERIAL TRUE)
  endif()
endif()
