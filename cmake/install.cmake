# Install rules, systemd units, drop-ins and the Debian package (CPack). docs/deploy.md.
#
#   cmake --install build --prefix /usr/local     # units in /usr/local/lib/systemd/system,
#                                                 # config in /usr/local/etc/litamin2
#   cd build && cpack -G DEB                      # litamin2_<version>_<arch>.deb, rooted at /usr
#
# Paths that must be absolute in the units (the binary, /etc/litamin2) are chosen at install
# time from the real prefix (deploy/cmake/install_system_files.cmake), so a build configured
# with the default /usr/local prefix still makes a correct /usr + /etc package.
include(GNUInstallDirs)

# Every tool and library declared with litamin2_add_tool / litamin2_add_library
# (cmake/litamin2_targets.cmake): tools into <prefix>/bin; with -DBUILD_SHARED_LIBS=ON the
# project's libraries into <prefix>/lib, where the tools' RPATH ($ORIGIN/../lib) finds them.
# A static build's tools carry the libraries inside, so nothing else is installed. The
# deploy_install and deploy_package tests check that every built tool lands in <prefix>/bin,
# and deploy_shared_install that a shared build's installed tools run.
get_property(_l2_tools GLOBAL PROPERTY LITAMIN2_TOOLS)
if(_l2_tools)
  install(TARGETS ${_l2_tools} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
get_property(_l2_libraries GLOBAL PROPERTY LITAMIN2_LIBRARIES)
foreach(lib ${_l2_libraries})
  get_target_property(_l2_type ${lib} TYPE)
  if(_l2_type STREQUAL "SHARED_LIBRARY")
    install(TARGETS ${lib} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  endif()
endforeach()

# Configuration and Fast DDS profiles -> <sysconfdir>/litamin2 (/etc/litamin2 for prefix /usr),
# systemd units -> <prefix>/lib/systemd/system; both at install time, see above.
file(GLOB LITAMIN2_CONFIG_FILES CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/config/*.yaml)
file(GLOB LITAMIN2_DDS_PROFILES CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/config/dds/*.xml)
install(CODE "
  set(LITAMIN2_DEPLOY_DIR \"${CMAKE_CURRENT_SOURCE_DIR}/deploy\")
  set(LITAMIN2_CONFIG_FILES \"${LITAMIN2_CONFIG_FILES}\")
  set(LITAMIN2_DDS_PROFILES \"${LITAMIN2_DDS_PROFILES}\")
  set(LITAMIN2_STAGE_DIR \"${CMAKE_CURRENT_BINARY_DIR}/deploy-stage\")
  include(\"${CMAKE_CURRENT_SOURCE_DIR}/deploy/cmake/install_system_files.cmake\")
")

# Drop-ins read by systemd-sysctl and systemd-sysusers (both also search /usr/local/lib).
install(FILES deploy/sysctl.d/60-litamin2.conf DESTINATION lib/sysctl.d)
install(FILES deploy/sysusers.d/litamin2.conf DESTINATION lib/sysusers.d)
install(FILES docs/deploy.md DESTINATION ${CMAKE_INSTALL_DOCDIR} OPTIONAL)

# ---- Debian package -------------------------------------------------------------------------
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME litamin2)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "litamin2")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
  "LiTAMIN2 LiDAR odometry and fleet mapping: DDS daemon, aggregator and tools")
set(CPACK_PACKAGE_DESCRIPTION
  "litamin2d runs one LiTAMIN2 tracker per point-cloud stream received over DDS (ROS 2\
 wire-compatible) and publishes odometry, map patches and status; litamin2-aggregator\
 stores the keyframes of every stream, closes loops within and between vehicles, optimises\
 the pose graph and keeps the global map. Both run by systemd (litamin2d.service,\
 litamin2d@.service, litamin2-aggregator.service). Also the offline tools litamin2-odometry,\
 litamin2-eval, litamin2-sim, litamin2-bench and the DDS replay tool.")
set(LITAMIN2_PACKAGE_MAINTAINER
  "litamin2 maintainers <maintainers@users.noreply.h-seed-88a194ff.example>"
  CACHE STRING "Maintainer field of the Debian package")
set(CPACK_PACKAGE_CONTACT "${LITAMIN2_PACKAGE_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${LITAMIN2_PACKAGE_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)          # dpkg-shlibdeps fills Depends
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "systemd")
# Debian packages live in /usr. The DEB generator installs with DESTDIR and prefix
# CPACK_PACKAGING_INSTALL_PREFIX by itself, so /etc/litamin2 lands inside the package and the
# install-time script sees /usr. CPACK_SET_DESTDIR=ON would use CMAKE_INSTALL_PREFIX instead
# (a /usr/local package from a default build): keep it off.
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_SET_DESTDIR OFF)
set(CPACK_STRIP_FILES ON)

# Maintainer scripts, and every /etc/litamin2 file as a conffile (kept on upgrade if edited).
set(_l2_conffiles "")
foreach(f ${LITAMIN2_CONFIG_FILES})
  get_filename_component(n ${f} NAME)
  string(APPEND _l2_conffiles "/etc/litamin2/${n}\n")
endforeach()
foreach(f ${LITAMIN2_DDS_PROFILES})
  get_filename_component(n ${f} NAME)
  string(APPEND _l2_conffiles "/etc/litamin2/dds/${n}\n")
endforeach()
set(_l2_control_extra
  ${CMAKE_CURRENT_SOURCE_DIR}/deploy/debian/postinst
  ${CMAKE_CURRENT_SOURCE_DIR}/deploy/debian/prerm
  ${CMAKE_CURRENT_SOURCE_DIR}/deploy/debian/postrm)
if(_l2_conffiles)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/deploy-control/conffiles "${_l2_conffiles}")
  list(APPEND _l2_control_extra ${CMAKE_CURRENT_BINARY_DIR}/deploy-control/conffiles)
endif()
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA "${_l2_control_extra}")
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION TRUE)

include(CPack)
