# litamin2d end to end over real DDS, inside a private network namespace (unshare -n, only lo
# up) and with the loopback-only transport profile: nothing can leave the machine.
#  - integration_daemon_replay: simulated scans -> litamin2-replay -> litamin2d -> daemon_probe;
#    every frame of two parallel streams gets one odometry message whose pose is bit-identical
#    to litamin2-odometry's; status reports no drop; SIGTERM exits 0 within 2 s; then the
#    shipped config's discovery (on another domain) starts a stream for a new publisher.
#  - integration_daemon_zero_copy: the same through the opt-in same-host zero-copy input
#    (litamin2-replay --zero-copy: PlainScan in loaned samples; litamin2d's zero_copy_topic:
#    data-sharing reader, loans on take): poses bit-identical to litamin2-odometry's, no bad
#    message or drop, data-sharing segments in /dev/shm.
#  - integration_daemon_two_sensors: litamin2-sim --second-sensor -> litamin2-replay of two topics
#    -> litamin2d with one stream of two `topics:` -> daemon_probe: one odometry message per
#    sweep, bounded error against the ground truth, merge counters complete; the rear sensor
#    stopping half-way (counted missing); both with motion within the sweep, deskewed.
#  - integration_daemon_lifecycle: --help/--version/--check-config, config errors, sd_notify
#    READY/WATCHDOG/STOPPING on a fake NOTIFY_SOCKET, SIGTERM/SIGINT exit 0 within 2 s.
if(TARGET litamin2d)
  add_executable(daemon_probe ${CMAKE_CURRENT_LIST_DIR}/daemon_probe/main.cpp)
  target_include_directories(daemon_probe PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_link_libraries(daemon_probe PRIVATE litamin2_dds litamin2_io CLI11::CLI11)

  add_test(NAME integration_daemon_lifecycle
    COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/daemon_lifecycle.sh ${CMAKE_BINARY_DIR}
      ${CMAKE_CURRENT_BINARY_DIR}/daemon_lifecycle ${CMAKE_SOURCE_DIR})
  set_tests_properties(integration_daemon_lifecycle PROPERTIES TIMEOUT 120 RUN_SERIAL TRUE)

  if(TARGET litamin2-replay AND TARGET litamin2-sim AND TARGET litamin2-odometry)
    add_test(NAME integration_daemon_replay
      COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/daemon_replay.sh ${CMAKE_BINARY_DIR}
        ${CMAKE_CURRENT_BINARY_DIR}/daemon_replay ${CMAKE_SOURCE_DIR})
    set_tests_properties(integration_daemon_replay PROPERTIES TIMEOUT 600 RUN_SERIAL TRUE)
    add_test(NAME integration_daemon_zero_copy
      COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/daemon_zero_copy.sh ${CMAKE_BINARY_DIR}
        ${CMAKE_CURRENT_BINARY_DIR}/daemon_zero_copy)
    set_tests_properties(integration_daemon_zero_copy PROPERTIES TIMEOUT 600 RUN_SERIAL TRUE)
    add_test(NAME integration_daemon_two_sensors
      COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/daemon_two_sensors.sh ${CMAKE_BINARY_DIR}
        ${CMAKE_CURRENT_BINARY_DIR}/daemon_two_sensors)
    set_tests_properties(integration_daemon_two_sensors PROPERTIES TIMEOUT 600 RUN_SERIAL TRUE)
  endif()
endif()
