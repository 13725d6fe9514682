# `metrosync animate` (docs/animate.md): Cairo draws the frames, an ffmpeg child process encodes
# them. Cairo is optional: found through pkg-config (Debian libcairo2-dev), it is linked into the
# animation code only:
#   metrosync-animate.so tools/report/animation.cpp  (the drawing; with animate_render.cpp the
#                        tools/cli/animate_render.cpp  files that see Cairo: a plugin)
#   metrosync_animate    tools/cli/animate.cpp       (the command; METROSYNC_HAVE_CAIRO=0 without
#                                                     Cairo: the command says it is unavailable)
# The files leave their folders' libraries, so that nothing else (the other commands, the Python
# module, the other tests) links Cairo, and `metrosync` loads it only when animate runs. Included at the end of CMakeLists.txt, once the folder
# libraries, the executable and the tests exist.
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(CAIRO IMPORTED_TARGET cairo)
endif()

foreach(pair "metrosync_tools_report;tools/report/animation.cpp"
             "metrosync_tools_cli;tools/cli/animate.cpp" "metrosync_tools_cli;tools/cli/animate_render.cpp"
             "metrosync_tools_cli;tools/cli/every_command.cpp")
  list(GET pair 0 lib)
  list(GET pair 1 file)
  get_target_property(srcs ${lib} SOURCES)
  list(REMOVE_ITEM srcs ${CMAKE_SOURCE_DIR}/${file})
  set_target_properties(${lib} PROPERTIES SOURCES "${srcs}")
endforeach()

add_library(metrosync_animate STATIC ${CMAKE_SOURCE_DIR}/tools/cli/animate.cpp)
target_include_directories(metrosync_animate PUBLIC ${CMAKE_SOURCE_DIR})
target_link_libraries(metrosync_animate PUBLIC metrosync_tools_cli)
metrosync_simbody_flags(metrosync_animate)
target_link_libraries(metrosync PRIVATE metrosync_animate)
target_link_libraries(metrosync-faults PRIVATE metrosync_animate)
# every command of `metrosync` (tools/cli/every_command.h) registers animate with the others: it
# leaves tools_cli too, for the executables and test_cli, which tests it
add_library(metrosync_every_command STATIC ${CMAKE_SOURCE_DIR}/tools/cli/every_command.cpp)
target_link_libraries(metrosync_every_command PUBLIC metrosync_animate)
metrosync_simbody_flags(metrosync_every_command)
foreach(t metrosync metrosync-faults test_cli)
  if(TARGET ${t})
    target_link_libraries(${t} PRIVATE metrosync_every_command)
  endif()
endforeach()
foreach(t test_animate test_hostile)  # test_hostile: every command's options (issue 29)
  if(TARGET ${t})
    target_link_libraries(${t} PRIVATE metrosync_animate)
  endif()
endforeach()
if(NOT CAIRO_FOUND)
  target_compile_definitions(metrosync_animate PUBLIC METROSYNC_HAVE_CAIRO=0)
  message(STATUS "animate: not available (needs Cairo: apt-get install libcairo2-dev)")
  return()
endif()
target_compile_definitions(metrosync_animate PUBLIC METROSYNC_HAVE_CAIRO=1)
message(STATUS "animate: Cairo ${CAIRO_VERSION}")
# The drawing (animation.cpp) and the render loop (animate_render.cpp) are the plugin
# metrosync-animate.so (tools/cli/animate_plugin.h), which `metrosync` loads when animate runs;
# test_animate links their objects directly.
add_library(metrosync_animate_plugin_entry OBJECT ${CMAKE_SOURCE_DIR}/tools/report/animation.cpp
                                                  ${CMAKE_SOURCE_DIR}/tools/cli/animate_render.cpp)
target_include_directories(metrosync_animate_plugin_entry PUBLIC ${CMAKE_SOURCE_DIR})
target_link_libraries(metrosync_animate_plugin_entry PUBLIC PkgConfig::CAIRO)
metrosync_simbody_flags(metrosync_animate_plugin_entry)
target_include_directories(metrosync_animate_plugin_entry PRIVATE
                           $<TARGET_PROPERTY:nlohmann_json::nlohmann_json,INTERFACE_INCLUDE_DIRECTORIES>
                           $<TARGET_PROPERTY:CLI11::CLI11,INTERFACE_INCLUDE_DIRECTORIES>)
add_library(metrosync_animate_plugin MODULE $<TARGET_OBJECTS:metrosync_animate_plugin_entry>)
target_link_libraries(metrosync_animate_plugin PRIVATE PkgConfig::CAIRO)
set_target_properties(metrosync_animate_plugin PROPERTIES PREFIX "" OUTPUT_NAME metrosync-animate
                      LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR})
add_dependencies(metrosync metrosync_animate_plugin)
install(TARGETS metrosync_animate_plugin LIBRARY DESTINATION ${METROSYNC_PLUGIN_INSTALL_DIR})
if(TARGET test_animate)
  target_sources(test_animate PRIVATE $<TARGET_OBJECTS:metrosync_animate_plugin_entry>)
  target_link_libraries(test_animate PRIVATE PkgConfig::CAIRO)
endif()
