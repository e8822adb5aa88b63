# The README's main job end to end on a short fleet (tests/integration/fleet_chain.sh).
if(TARGET litamin2d AND TARGET litamin2-aggregator AND TARGET litamin2-sim
   AND TARGET litamin2-replay AND TARGET daemon_probe AND TARGET map_odom_probe)
  add_test(NAME integration_fleet_chain
    COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/fleet_chain.sh ${CMAKE_BINARY_DIR}
      ${CMAKE_CURRENT_BINARY_DIR}/fleet_chain ${CMAKE_SOURCE_DIR})
  set_tests_properties(integration_fleet_chain PROPERTIES TIMEOUT 900 RUN_SERIAL TRUE)
endif()
