# `cmake --install` and the Debian package (CPack), docs/install.md:
#   bin/metrosync (and bin/metrosync-mpi with MPI), lib/<arch>/metrosync/*.so (its plugins), share/man/man1/metrosync.1.gz (help2man, from the binary's --help texts),
#   bash and zsh completion (from the same texts), share/metrosync/rigs (the example rigs),
#   share/doc/metrosync (README, CHANGELOG, docs/).
# The generated files are made after the binary is linked, so they never disagree with it.
include(GNUInstallDirs)

set(METROSYNC_GENERATED ${CMAKE_BINARY_DIR}/install-files)
add_custom_command(
  OUTPUT ${METROSYNC_GENERATED}/metrosync.bash ${METROSYNC_GENERATED}/_metrosync
  COMMAND bash ${CMAKE_SOURCE_DIR}/tools/install/completions.sh $<TARGET_FILE:metrosync>
          ${METROSYNC_GENERATED}
  DEPENDS metrosync ${CMAKE_SOURCE_DIR}/tools/install/completions.sh
  COMMENT "Generating shell completions from metrosync --help")
set(install_generated ${METROSYNC_GENERATED}/metrosync.bash ${METROSYNC_GENERATED}/_metrosync)

find_program(HELP2MAN help2man)
find_program(GZIP gzip)
if(HELP2MAN AND GZIP)
  add_custom_command(
    OUTPUT ${METROSYNC_GENERATED}/metrosync.1.gz
    COMMAND bash ${CMAKE_SOURCE_DIR}/tools/install/manpage.sh $<TARGET_FILE:metrosync>
            ${METROSYNC_GENERATED}/metrosync.1
    COMMAND ${GZIP} -9nf ${METROSYNC_GENERATED}/metrosync.1
    DEPENDS metrosync ${CMAKE_SOURCE_DIR}/tools/install/manpage.sh
    COMMENT "Generating the man page from metrosync --help (help2man)")
  list(APPEND install_generated ${METROSYNC_GENERATED}/metrosync.1.gz)
  install(FILES ${METROSYNC_GENERATED}/metrosync.1.gz DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
else()
  message(STATUS "help2man not found: no man page (apt-get install help2man)")
endif()
add_custom_target(metrosync_install_files ALL DEPENDS ${install_generated})

install(TARGETS metrosync RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# metrosync-mpi beside it, when MPI was found (tools/cli/mpi.cmake): `metrosync sweep` started
# by mpirun execs it from its own folder (tools/cli/mpi_forward.h)
if(TARGET metrosync-mpi)
  # MPI's libraries keep their folder on the installed binary's RUNPATH as on the build tree's
  # (Debian's openmpi/lib; CMake cannot take that entry out of the binary, and other systems need
  # it)
  set_target_properties(metrosync-mpi PROPERTIES INSTALL_RPATH_USE_LINK_PATH ON)
  install(TARGETS metrosync-mpi RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
# the plugins metrosync loads on demand (sim/engines/plugin_loader.h): <libdir>/metrosync, which
# the executable finds relative to itself (METROSYNC_PLUGIN_RELATIVE_DIR)
install(TARGETS ${METROSYNC_PLUGINS} LIBRARY DESTINATION ${METROSYNC_PLUGIN_INSTALL_DIR})
install(FILES ${METROSYNC_GENERATED}/metrosync.bash
        DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions RENAME metrosync)
install(FILES ${METROSYNC_GENERATED}/_metrosync
        DESTINATION ${CMAKE_INSTALL_DATADIR}/zsh/vendor-completions)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/yaml/rigs/ DESTINATION ${CMAKE_INSTALL_DATADIR}/metrosync/rigs
        FILES_MATCHING PATTERN "*.yaml")
install(FILES ${CMAKE_SOURCE_DIR}/README.md ${CMAKE_SOURCE_DIR}/CHANGELOG.md
        DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${CMAKE_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs
        PATTERN "*.csv" EXCLUDE)

# The Debian package: `cpack -G DEB` in the build folder. Its library dependencies are read off
# the binary by dpkg-shlibdeps (package dpkg-dev); gnuplot draws the plots at run time.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME metrosync)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "metrosync developers <metrosync@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "coupled metronomes on a moving platform with dry friction: full model and slow flow")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "gnuplot-nox | gnuplot")
if(METROSYNC_PYTHON_DEB_DEPENDS)  # the Python module is in the package (tools/python/python.cmake)
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS ", ${METROSYNC_PYTHON_DEB_DEPENDS}")
  set(CPACK_DEBIAN_PACKAGE_SUGGESTS ${METROSYNC_PYTHON_DEB_SUGGESTS})
endif()
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
include(CPack)
