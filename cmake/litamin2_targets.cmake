# How the project's libraries and tools are declared. Every library's CMakeLists.txt sits beside
# its sources (src/<library>/CMakeLists.txt); every tool's in tools/<tool>/.
#
#   litamin2_add_library(<name> SOURCES <.cpp...> [PUBLIC <deps...>] [PRIVATE <deps...>])
#   litamin2_add_tool(<name> SOURCES <.cpp...> LIBRARIES <deps...>)
#
# Both record the target in a global list that cmake/install.cmake installs, so that a target
# declared anywhere is installed: shared libraries (-DBUILD_SHARED_LIBS=ON) into <prefix>/lib,
# tools into <prefix>/bin with an RPATH of $ORIGIN/../lib (libraries: $ORIGIN).
include(GNUInstallDirs)

function(litamin2_add_library name)
  cmake_parse_arguments(arg "" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  add_library(${name} ${arg_SOURCES})
  target_include_directories(${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${name} PUBLIC ${arg_PUBLIC} PRIVATE ${arg_PRIVATE})
  # A shared library finds the project libraries it needs beside itself (RUNPATH is not
  # transitive: the tools' $ORIGIN/../lib does not reach a library's own dependencies).
  set_target_properties(${name} PROPERTIES POSITION_INDEPENDENT_CODE ON INSTALL_RPATH "$ORIGIN")
  set_property(GLOBAL APPEND PROPERTY LITAMIN2_LIBRARIES ${name})
endfunction()

function(litamin2_add_tool name)
  cmake_parse_arguments(arg "" "" "SOURCES;LIBRARIES" ${ARGN})
  add_executable(${name} ${arg_SOURCES})
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tools)
  target_link_libraries(${name} PRIVATE ${arg_LIBRARIES})
  set_target_properties(${name} PROPERTIES INSTALL_RPATH "$ORIGIN/../${CMAKE_INSTALL_LIBDIR}")
  set_property(GLOBAL APPEND PROPERTY LITAMIN2_TOOLS ${name})
endfunction()
