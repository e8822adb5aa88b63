# Several hosts in private network namespaces (tests/integration/multihost.sh, issue 15): needs
# root for ip netns, skipped (77) without. The delay scenario needs /dev/net/tun (TAP devices,
# tests/link_emulator).
if(TARGET litamin2d AND TARGET litamin2-aggregator AND TARGET litamin2-sim
   AND TARGET litamin2-replay AND TARGET daemon_probe AND TARGET aggregator_probe
   AND TARGET link_emulator)
  add_test(NAME integration_multihost
    COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/multihost.sh ${CMAKE_BINARY_DIR}
      ${CMAKE_CURRENT_BINARY_DIR}/multihost)
  set_tests_properties(integration_multihost PROPERTIES TIMEOUT 900 RUN_SERIAL TRUE
    SKIP_RETURN_CODE 77)
endif()
