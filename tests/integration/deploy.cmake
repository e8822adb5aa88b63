# Deploy checks (docs/deploy.md): units, install tree, Debian package. Included by
# tests/integration/CMakeLists.txt; every built executable of the product is expected in the
# install tree and in the package.
set(_deploy_bins "")
set(_deploy_units_args "")
foreach(t litamin2-odometry litamin2-eval litamin2-sim litamin2-bench litamin2-replay litamin2d
    litamin2-aggregator)
  if(TARGET ${t})
    list(APPEND _deploy_bins ${t})
    list(APPEND _deploy_units_args "${t}=$<TARGET_FILE:${t}>")
  endif()
endforeach()

# systemd-analyze verify + offline security score of every unit, sysusers/sysctl drop-ins and
# maintainer scripts. Until litamin2d exists the units are verified with a stand-in ExecStart.
add_test(NAME deploy_units
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/deploy_units.sh ${CMAKE_SOURCE_DIR}/deploy
    ${CMAKE_CURRENT_BINARY_DIR}/deploy_units ${_deploy_units_args})
set_tests_properties(deploy_units PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 60)

# cmake --install with prefixes /usr and /usr/local into scratch DESTDIRs.
add_test(NAME deploy_install
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/deploy_install.sh ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR}
    ${CMAKE_CURRENT_BINARY_DIR}/deploy_install ${_deploy_bins})
set_tests_properties(deploy_install PROPERTIES TIMEOUT 120 RESOURCE_LOCK litamin2_install)

# cpack -G DEB into a scratch folder, checked with dpkg-deb. Needs binaries (their shared
# libraries make the package's Depends), so only when the tools are built.
if(_deploy_bins)
add_test(NAME deploy_package
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/deploy_package.sh ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR}
    ${CMAKE_CURRENT_BINARY_DIR}/deploy_package ${PROJECT_VERSION} ${_deploy_bins})
set_tests_properties(deploy_package PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300
  RESOURCE_LOCK litamin2_install)
endif()

# The maintainer scripts run for real in a private mount namespace (needs root, else skipped).
add_test(NAME deploy_maintainer_scripts
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/deploy_maintainer_scripts.sh ${CMAKE_SOURCE_DIR}
    ${CMAKE_CURRENT_BINARY_DIR}/deploy_maintainer_scripts)
set_tests_properties(deploy_maintainer_scripts PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 60)

# A -DBUILD_SHARED_LIBS=ON build of the product (tests and benchmarks off) installed into a
# scratch DESTDIR: every library lands beside the tools and the installed tools run from there
# alone; and -DLITAMIN2_BUILD_TOOLS=OFF still defines every library. A build of its own (a few
# minutes on 2 cores), so it runs alone.
add_test(NAME deploy_shared_install
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/deploy_shared_install.sh ${PROJECT_SOURCE_DIR}
    ${CMAKE_CURRENT_BINARY_DIR}/deploy_shared_install)
# Label build_variant: left out of scripts/test.sh (CI) unless LITAMIN2_TEST_BUILD_VARIANTS=1,
# its whole second build took 10-22 min of a 54 min CI run.
set_tests_properties(deploy_shared_install PROPERTIES TIMEOUT 3600 RUN_SERIAL TRUE
  LABELS build_variant)
