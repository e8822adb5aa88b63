# Untrusted input over real DDS, and DDS-Security end to end, inside a private network namespace
# (unshare -n, only lo up). docs/security.md.
#  - integration_malformed_cdr: raw_cdr_writer sends CDR payloads with a bad bool, a truncated
#    sequence and a sequence length beyond the payload to litamin2d (rt/<stream>/points) and
#    litamin2-aggregator (map patches, odometry): both keep running, count each sample in their
#    status, and keep serving a good stream.
#  - integration_security: the whole chain with DDS-Security on (scripts/litamin2-pki): valid
#    participants work; one without a valid certificate gets no odometry and changes nothing;
#    one without permission for a topic is refused; the loopback capture holds no plaintext of a
#    marker stream id; a tampered, unsigned, expired or mismatched file stops a process at
#    start naming it.
#  - integration_stream_binding: map-patch stream ids bound to the writer's partition, with
#    and without DDS-Security (a daemon identity cannot write another daemon's partition; a
#    patch naming a stream outside its writer's partition is rejected and counted).
#  - integration_patch_payload_bound: a 32 MB patch against a 1 MB payload limit: reassembled
#    and rejected (peak RSS + the sample's size) by default, dropped by Fast DDS before any allocation with
#    limits.fixed_patch_payloads.
if(TARGET litamin2d AND TARGET litamin2-aggregator)
  add_executable(raw_cdr_writer ${CMAKE_CURRENT_LIST_DIR}/raw_cdr_writer/main.cpp)
  target_include_directories(raw_cdr_writer PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_link_libraries(raw_cdr_writer PRIVATE litamin2_dds CLI11::CLI11)
  # Records a DiagnosticArray status topic (both processes' status) into a file.
  add_executable(status_probe ${CMAKE_CURRENT_LIST_DIR}/status_probe/main.cpp)
  target_include_directories(status_probe PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_link_libraries(status_probe PRIVATE litamin2_dds CLI11::CLI11)

  if(TARGET litamin2-replay AND TARGET litamin2-sim)
    add_test(NAME integration_malformed_cdr
      COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/malformed_cdr.sh ${CMAKE_BINARY_DIR}
        ${CMAKE_CURRENT_BINARY_DIR}/malformed_cdr ${CMAKE_SOURCE_DIR})
    set_tests_properties(integration_malformed_cdr PROPERTIES TIMEOUT 300 RUN_SERIAL TRUE)
    add_test(NAME integration_security
      COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/security.sh ${CMAKE_BINARY_DIR}
        ${CMAKE_CURRENT_BINARY_DIR}/security ${CMAKE_SOURCE_DIR})
    set_tests_properties(integration_security PROPERTIES TIMEOUT 600 RUN_SERIAL TRUE)
    add_test(NAME integration_stream_binding
      COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/stream_binding.sh ${CMAKE_BINARY_DIR}
        ${CMAKE_CURRENT_BINARY_DIR}/stream_binding ${CMAKE_SOURCE_DIR})
    set_tests_properties(integration_stream_binding PROPERTIES TIMEOUT 600 RUN_SERIAL TRUE)
    add_test(NAME integration_patch_payload_bound
      COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/patch_payload_bound.sh ${CMAKE_BINARY_DIR}
        ${CMAKE_CURRENT_BINARY_DIR}/patch_payload_bound ${CMAKE_SOURCE_DIR})
    set_tests_properties(integration_patch_payload_bound PROPERTIES TIMEOUT 300 RUN_SERIAL TRUE)
  endif()
endif()
