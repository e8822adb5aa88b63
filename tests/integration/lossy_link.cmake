# Packet loss on the daemon -> aggregator link during ingest (tests/integration/lossy_link.sh,
# issue 15): the fleet chain with LITAMIN2_TEST_UDP_LOSS_PERCENT=10 on litamin2d and the
# aggregator, against a lossless baseline, in a private network namespace; 0 keyframes lost.
if(TARGET litamin2d AND TARGET litamin2-aggregator AND TARGET litamin2-sim
   AND TARGET litamin2-replay AND TARGET daemon_probe)
  add_test(NAME integration_lossy_link
    COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/lossy_link.sh ${CMAKE_BINARY_DIR}
      ${CMAKE_CURRENT_BINARY_DIR}/lossy_link)
  set_tests_properties(integration_lossy_link PROPERTIES TIMEOUT 600 RUN_SERIAL TRUE)
endif()
