# Offline SLAM (litamin2-odometry --loop-closure) on a simulated KITTI 00 section with a loop.
if(TARGET litamin2-sim AND TARGET litamin2-odometry AND TARGET litamin2-eval)
  add_test(NAME integration_slam_loop_closure
    COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/slam_loop_closure.sh ${CMAKE_BINARY_DIR}/tools
      ${CMAKE_CURRENT_BINARY_DIR}/slam_loop_closure ${CMAKE_SOURCE_DIR}/../shared)
  set_tests_properties(integration_slam_loop_closure PROPERTIES TIMEOUT 900 SKIP_RETURN_CODE 77)
endif()
