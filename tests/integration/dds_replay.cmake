# DDS replay: litamin2-replay publishes small sequences, a test subscriber checks every scan
# arrives bit-identical. Runs inside a private network namespace when possible (unshare -n),
# always with the loopback-only profile.
if(TARGET litamin2_dds AND TARGET litamin2-replay)
  add_executable(dds_replay_subscriber ${CMAKE_CURRENT_LIST_DIR}/dds_replay_subscriber.cpp)
  target_link_libraries(dds_replay_subscriber PRIVATE litamin2_dds litamin2_io spdlog::spdlog)
  add_test(NAME integration_dds_replay
    COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/dds_replay.sh $<TARGET_FILE:litamin2-replay>
      $<TARGET_FILE:dds_replay_subscriber> ${CMAKE_CURRENT_BINARY_DIR}/dds_replay)
  set_tests_properties(integration_dds_replay PROPERTIES TIMEOUT 300)
endif()
