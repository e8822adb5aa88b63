# Runs at install time (cmake --install, cpack), included from cmake/install.cmake's install(CODE).
# Here CMAKE_INSTALL_PREFIX is the prefix really installed to, so the units and /etc paths follow
# it: prefix /usr (the Debian package) -> /usr/bin/litamin2d and /etc/litamin2; any other prefix P
# -> P/bin/litamin2d and P/etc/litamin2 (the GNU rule). file(INSTALL) applies DESTDIR itself.
#
# Inputs: LITAMIN2_DEPLOY_DIR (source deploy/), LITAMIN2_CONFIG_FILES, LITAMIN2_DDS_PROFILES,
#         LITAMIN2_STAGE_DIR (a scratch folder in the build tree).
string(REGEX REPLACE "/+$" "" _l2_prefix "${CMAKE_INSTALL_PREFIX}")
if(_l2_prefix STREQUAL "" OR _l2_prefix STREQUAL "/usr")
  set(_l2_confdir /etc/litamin2)
else()
  set(_l2_confdir ${_l2_prefix}/etc/litamin2)
endif()
set(_l2_prefix_dir "${_l2_prefix}")
if(_l2_prefix_dir STREQUAL "")
  set(_l2_prefix_dir /usr)
endif()

# Configuration (conffiles in the Debian package) and Fast DDS XML profiles.
if(LITAMIN2_CONFIG_FILES)
  file(INSTALL ${LITAMIN2_CONFIG_FILES} DESTINATION ${_l2_confdir}
    PERMISSIONS OWNER_READ OWNER_WRITE GROUP_READ WORLD_READ)
endif()
if(LITAMIN2_DDS_PROFILES)
  file(INSTALL ${LITAMIN2_DDS_PROFILES} DESTINATION ${_l2_confdir}/dds
    PERMISSIONS OWNER_READ OWNER_WRITE GROUP_READ WORLD_READ)
endif()

# systemd units: the sources name /usr/bin, /usr/share and /etc/litamin2; rewritten for other
# prefixes (nothing changes for /usr).
# One scratch folder per destination: concurrent installs (tests) must not share files.
string(MD5 _l2_hash "$ENV{DESTDIR}|${_l2_prefix}")
set(_l2_stage ${LITAMIN2_STAGE_DIR}/${_l2_hash})
file(MAKE_DIRECTORY ${_l2_stage})
file(GLOB _l2_units ${LITAMIN2_DEPLOY_DIR}/systemd/*.service)
foreach(_l2_unit ${_l2_units})
  get_filename_component(_l2_name ${_l2_unit} NAME)
  file(READ ${_l2_unit} _l2_text)
  string(REPLACE "/usr/bin/" "${_l2_prefix_dir}/bin/" _l2_text "${_l2_text}")
  string(REPLACE "/usr/share/" "${_l2_prefix_dir}/share/" _l2_text "${_l2_text}")
  string(REPLACE "/etc/litamin2/" "${_l2_confdir}/" _l2_text "${_l2_text}")
  file(WRITE ${_l2_stage}/${_l2_name} "${_l2_text}")
  file(INSTALL ${_l2_stage}/${_l2_name} DESTINATION ${_l2_prefix}/lib/systemd/system
    PERMISSIONS OWNER_READ OWNER_WRITE GROUP_READ WORLD_READ)
endforeach()
