# `metrosync animate` (docs/animate.md): Cairo draws the frames, an ffmpeg child process encodes
# them. Cairo is optional: found through pkg-config (Debian libcairo2-dev), it is linked into the
# animation code only:
#   metrosync_animation  tools/report/animation.cpp  (the drawing; the one file that sees Cairo)
#   metrosync_animate    tools/cli/animate.cpp       (the command; METROSYNC_HAVE_CAIRO=0 without
#                                                     Cairo: the command says it is unavailable)
# Both files leave their folders' libraries, so that nothing else (the other commands, the Python
# module, the other tests) links Cairo. Included at the end of CMakeLists.txt, once the folder
# libraries, the executable and the tests exist.
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(CAIRO IMPORTED_TARGET cairo)
endif()

foreach(pair "metrosync_tools_report;tools/report/animation.cpp"
             "metrosync_tools_cli;tools/cli/animate.cpp")
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
if(CAIRO_FOUND)
  add_library(metrosync_animation STATIC ${CMAKE_SOURCE_DIR}/tools/report/animation.cpp)
  target_include_directories(metrosync_animation PUBLIC ${CMAKE_SOURCE_DIR})
  target_link_libraries(metrosync_animation PUBLIC metrosync_tools_report PkgConfig::CAIRO)
  target_link_libraries(metrosync_animate PUBLIC metrosync_animation)
  target_compile_definitions(metrosync_animate PUBLIC METROSYNC_HAVE_CAIRO=1)
  message(STATUS "animate: Cairo ${CAIRO_VERSION}")
else()
  target_compile_definitions(metrosync_animate PUBLIC METROSYNC_HAVE_CAIRO=0)
  message(STATUS "animate: not available (needs Cairo: apt-get install libcairo2-dev)")
endif()

target_link_libraries(metrosync PRIVATE metrosync_animate)
if(TARGET test_animate)
  target_link_libraries(test_animate PRIVATE metrosync_animate)
endif()
