# The core as an installed CMake package (docs/library.md): `find_package(metrosync)` gives the
# targets metrosync::core (everything below) and one per library (metrosync::models, ...), their
# headers under include/metrosync with the repository's paths ("models/network.h"), the static
# libraries under <libdir>/metrosync-dev. The engines in the package are the direct engine and the
# slow flow; the simbody engine is the plugin of the `metrosync` executable and not in it.
include(CMakePackageConfigHelpers)

set(METROSYNC_PACKAGE_LIBRARIES
    base contact models sim_ode sim_parallel sim_record sim_events sim_engines_direct
    sim_engines_slow_flow sim_engines sim_analysis_continuation sim_analysis_periodic_orbit
    sim_analysis yaml)
set(METROSYNC_PACKAGE_FOLDERS base contact models sim/ode sim/parallel sim/record sim/events
    sim/engines/direct sim/engines/slow_flow sim/engines sim/analysis/continuation
    sim/analysis/periodic_orbit sim/analysis yaml)
set(METROSYNC_PACKAGE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/metrosync)

set(_targets "")
foreach(lib ${METROSYNC_PACKAGE_LIBRARIES})
  list(APPEND _targets metrosync_${lib})
  set_target_properties(metrosync_${lib} PROPERTIES EXPORT_NAME ${lib})
endforeach()
add_library(metrosync_core INTERFACE)
target_link_libraries(metrosync_core INTERFACE ${_targets})
set_target_properties(metrosync_core PROPERTIES EXPORT_NAME core)
install(TARGETS ${_targets} metrosync_core EXPORT metrosyncTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}/metrosync-dev COMPONENT dev)
# each folder's headers (not its subfolders': those are libraries of their own, or not in the
# package, as sim/engines/simbody)
foreach(folder ${METROSYNC_PACKAGE_FOLDERS})
  file(GLOB _headers ${CMAKE_SOURCE_DIR}/${folder}/*.h)
  install(FILES ${_headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/metrosync/${folder}
          COMPONENT dev)
endforeach()
install(EXPORT metrosyncTargets NAMESPACE metrosync:: DESTINATION ${METROSYNC_PACKAGE_DIR}
        COMPONENT dev)
configure_package_config_file(${CMAKE_SOURCE_DIR}/tools/install/metrosyncConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/package/metrosyncConfig.cmake
                              INSTALL_DESTINATION ${METROSYNC_PACKAGE_DIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/package/metrosyncConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/package/metrosyncConfig.cmake
              ${CMAKE_BINARY_DIR}/package/metrosyncConfigVersion.cmake
        DESTINATION ${METROSYNC_PACKAGE_DIR} COMPONENT dev)

# The test that installs the package and builds examples/ against it (tests/package/)
if(GTest_FOUND)
  add_test(NAME package:examples
           COMMAND bash ${CMAKE_SOURCE_DIR}/tests/package/check_package.sh ${CMAKE_BINARY_DIR})
  set_tests_properties(package:examples PROPERTIES LABELS slow TIMEOUT 900)
endif()
