# Interop with an independent DDS implementation (DESIGN.md section 4): cyclone_client, written
# against the Cyclone DDS C API only, publishes simulated scans as sensor_msgs/PointCloud2 into
# litamin2d and reads its nav_msgs/Odometry; every pose must be bit-identical to
# litamin2-odometry's. Runs inside a private network namespace (unshare -n, only lo up), with
# Cyclone configured loopback-only and unicast-only (cyclone_loopback.xml) and the daemon on its
# loopback profile.
#
# Cyclone's types come from the project's own IDL files: ros2_dds_idl.cmake rewrites each into
# the ROS 2 wire names (module dds_, trailing underscore: sensor_msgs::msg::dds_::PointCloud2_,
# as fastddsgen -typeros2 registers them for the daemon) and idlc compiles the copies to C.
find_package(CycloneDDS QUIET)
find_program(LITAMIN2_CYCLONE_IDLC idlc)
if(NOT CycloneDDS_FOUND OR NOT LITAMIN2_CYCLONE_IDLC)
  message(STATUS "Cyclone DDS (cyclonedds-dev, cyclonedds-tools) not found: "
                 "no integration_cyclone_interop test")
elseif(TARGET litamin2d AND TARGET litamin2-sim AND TARGET litamin2-odometry AND
       TARGET litamin2-aggregator)
  # idlc generates C; the project itself is C++ only.
  enable_language(C)
  set(cyclone_dir ${CMAKE_CURRENT_LIST_DIR}/cyclone_client)
  set(cyclone_gen ${CMAKE_CURRENT_BINARY_DIR}/cyclone_types)
  # Topic types and every type they contain, includes before includers.
  set(cyclone_types
    builtin_interfaces/msg/Time std_msgs/msg/Header
    sensor_msgs/msg/PointField sensor_msgs/msg/PointCloud2
    geometry_msgs/msg/Point geometry_msgs/msg/Quaternion geometry_msgs/msg/Pose
    geometry_msgs/msg/PoseWithCovariance geometry_msgs/msg/Vector3 geometry_msgs/msg/Twist
    geometry_msgs/msg/TwistWithCovariance nav_msgs/msg/Odometry
    geometry_msgs/msg/Transform geometry_msgs/msg/TransformStamped tf2_msgs/msg/TFMessage
    diagnostic_msgs/msg/KeyValue diagnostic_msgs/msg/DiagnosticStatus
    diagnostic_msgs/msg/DiagnosticArray)

  set(cyclone_idl_copies "")
  foreach(type ${cyclone_types})
    set(copy ${cyclone_gen}/idl/${type}.idl)
    get_filename_component(copy_dir ${copy} DIRECTORY)
    add_custom_command(
      OUTPUT ${copy}
      COMMAND ${CMAKE_COMMAND} -E make_directory ${copy_dir}
      COMMAND ${CMAKE_COMMAND} -DINPUT=${CMAKE_SOURCE_DIR}/idl/${type}.idl -DOUTPUT=${copy}
              -P ${cyclone_dir}/ros2_dds_idl.cmake
      DEPENDS ${CMAKE_SOURCE_DIR}/idl/${type}.idl ${cyclone_dir}/ros2_dds_idl.cmake
      COMMENT "ROS 2 wire names: ${type}.idl"
      VERBATIM)
    list(APPEND cyclone_idl_copies ${copy})
  endforeach()

  set(cyclone_sources "")
  foreach(type ${cyclone_types})
    set(c_file ${cyclone_gen}/c/${type}.c)
    set(h_file ${cyclone_gen}/c/${type}.h)
    # An IDL copy includes others: every copy is a dependency of every idlc run.
    add_custom_command(
      OUTPUT ${c_file} ${h_file}
      COMMAND ${CMAKE_COMMAND} -E make_directory ${cyclone_gen}/c
      COMMAND ${LITAMIN2_CYCLONE_IDLC} -x final -I ${cyclone_gen}/idl -b ${cyclone_gen}/idl
              -o ${cyclone_gen}/c ${cyclone_gen}/idl/${type}.idl
      DEPENDS ${cyclone_idl_copies}
      WORKING_DIRECTORY ${cyclone_gen}
      COMMENT "idlc: ${type}.idl"
      VERBATIM)
    list(APPEND cyclone_sources ${c_file})
  endforeach()

  add_library(litamin2_cyclone_types STATIC ${cyclone_sources})
  target_include_directories(litamin2_cyclone_types PUBLIC ${cyclone_gen}/c)
  target_link_libraries(litamin2_cyclone_types PUBLIC CycloneDDS::ddsc)
  # Generated code is not ours to fix.
  target_compile_options(litamin2_cyclone_types PRIVATE -w)

  add_executable(cyclone_client ${cyclone_dir}/main.cpp)
  target_link_libraries(cyclone_client PRIVATE litamin2_cyclone_types litamin2_io Eigen3::Eigen
    CLI11::CLI11)

  add_test(NAME integration_cyclone_interop
    COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/cyclone_interop.sh
      $<TARGET_FILE:litamin2d> $<TARGET_FILE:litamin2-sim> $<TARGET_FILE:litamin2-odometry>
      $<TARGET_FILE:cyclone_client> ${CMAKE_CURRENT_LIST_DIR}/cyclone_loopback.xml
      ${CMAKE_CURRENT_BINARY_DIR}/cyclone_interop)
  set_tests_properties(integration_cyclone_interop PROPERTIES TIMEOUT 600 RUN_SERIAL TRUE)

  # rt/tf and rt/tf_static as a ROS 2 node reads them: cyclone_tf_reader (Cyclone only) checks
  # every odom -> base_link transform against the odometry of the same stamp, bit for bit, and a
  # late reader of the transient-local rt/tf_static gets base_link -> sensor (the extrinsic);
  # litamin2-aggregator's map -> <stream>/odom arrive at odometry stamps.
  add_executable(cyclone_tf_reader ${CMAKE_CURRENT_LIST_DIR}/cyclone_tf_reader/main.cpp)
  target_link_libraries(cyclone_tf_reader PRIVATE litamin2_cyclone_types CLI11::CLI11)
  add_test(NAME integration_cyclone_tf
    COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/cyclone_tf.sh
      $<TARGET_FILE:litamin2d> $<TARGET_FILE:litamin2-aggregator> $<TARGET_FILE:litamin2-sim>
      $<TARGET_FILE:cyclone_client> $<TARGET_FILE:cyclone_tf_reader> ${CMAKE_CURRENT_LIST_DIR}/cyclone_loopback.xml
      ${CMAKE_CURRENT_BINARY_DIR}/cyclone_tf)
  set_tests_properties(integration_cyclone_tf PROPERTIES TIMEOUT 600 RUN_SERIAL TRUE)

  # The Prometheus endpoint (/metrics parsed as Prometheus text, /readyz, /healthz, a bind
  # failure) of both processes, and their status on rt/diagnostics read by Cyclone DDS as a
  # ROS 2 diagnostics tool would.
  add_executable(cyclone_diagnostics_reader
    ${CMAKE_CURRENT_LIST_DIR}/cyclone_diagnostics_reader/main.cpp)
  target_link_libraries(cyclone_diagnostics_reader PRIVATE litamin2_cyclone_types CLI11::CLI11)
  add_test(NAME integration_metrics
    COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/metrics.sh
      $<TARGET_FILE:litamin2d> $<TARGET_FILE:litamin2-aggregator> $<TARGET_FILE:litamin2-sim>
      $<TARGET_FILE:cyclone_client> $<TARGET_FILE:cyclone_diagnostics_reader>
      ${CMAKE_CURRENT_LIST_DIR}/cyclone_loopback.xml ${CMAKE_CURRENT_LIST_DIR}/prometheus_check.py
      ${CMAKE_CURRENT_BINARY_DIR}/metrics)
  set_tests_properties(integration_metrics PROPERTIES TIMEOUT 600 RUN_SERIAL TRUE)
endif()
