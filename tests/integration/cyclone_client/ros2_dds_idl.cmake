# cmake -DINPUT=<pkg>/msg/<Type>.idl -DOUTPUT=<file> -P ros2_dds_idl.cmake
#
# Rewrites one of the project's ROS 2 IDL files (module <pkg>::msg, struct <Type>) into the
# names ROS 2 puts on the wire, for Cyclone DDS's idlc: every struct goes into an extra
# `module dds_` and gets a trailing underscore, and every reference <pkg>::msg::<Type> becomes
# <pkg>::msg::dds_::<Type>_. idlc then registers `sensor_msgs::msg::dds_::PointCloud2_`, the
# name fastddsgen -typeros2 registers for the daemon (and rmw_cyclonedds for ROS 2 nodes).
# ROS 2 constant modules (<Type>_Constants) are left out: idlc 0.10 rejects names such as INT8
# (they collide with the IDL keyword int8, identifiers being case-insensitive), and constants
# do not go on the wire.
# Expects the layout of the files in idl/: `module <pkg> { module msg { ... }; };`.
if(NOT INPUT OR NOT OUTPUT)
  message(FATAL_ERROR "usage: cmake -DINPUT=FILE.idl -DOUTPUT=FILE.idl -P ros2_dds_idl.cmake")
endif()
file(READ ${INPUT} text)
# Comments may mention type names: drop them before renaming.
string(REGEX REPLACE "//[^\n]*" "" text "${text}")

string(REGEX REPLACE "module[ \t\r\n]+[A-Za-z0-9_]+_Constants[ \t\r\n]*{[^}]*}[ \t\r\n]*;" ""
  text "${text}")

string(REGEX MATCHALL "module[ \t\r\n]+msg[ \t\r\n]*{" msg_modules "${text}")
list(LENGTH msg_modules count)
if(NOT count EQUAL 1)
  message(FATAL_ERROR "${INPUT}: expected exactly one 'module msg {', found ${count}")
endif()
if(NOT text MATCHES "};[ \t\r\n]*};[ \t\r\n]*$")
  message(FATAL_ERROR "${INPUT}: does not end with the closing '};' of modules msg and <pkg>")
endif()

string(REGEX REPLACE "([A-Za-z0-9_]+)::msg::([A-Za-z0-9_]+)" "\\1::msg::dds_::\\2_" text
  "${text}")
string(REGEX REPLACE "struct[ \t\r\n]+([A-Za-z0-9_]+)[ \t\r\n]*{" "struct \\1_ {" text "${text}")
string(REGEX REPLACE "module[ \t\r\n]+msg[ \t\r\n]*{" "module msg {\nmodule dds_ {" text
  "${text}")
string(REGEX REPLACE "};[ \t\r\n]*};[ \t\r\n]*$" "};\n};\n};\n" text "${text}")

file(WRITE ${OUTPUT}.tmp "// Generated from ${INPUT} by ros2_dds_idl.cmake: do not edit.\n${text}")
file(RENAME ${OUTPUT}.tmp ${OUTPUT})
