# ros2/litamin2 (the ROS 2 interface package of the project's types) cannot be built here (no
# ROS 2); this checks what can be: package.xml is well-formed with the package named as the IDL
# module, and its CMakeLists lists every IDL file of idl/litamin2/msg, so a new type is not
# forgotten in the ROS 2 package.
find_package(Python3 COMPONENTS Interpreter QUIET)
if(Python3_Interpreter_FOUND)
  add_test(NAME ros2_package_lists_every_idl
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_LIST_DIR}/ros2_package_check.py
      ${CMAKE_SOURCE_DIR}/ros2/litamin2 ${CMAKE_SOURCE_DIR}/idl/litamin2/msg)
endif()
