# tools/fuzz (issue 39, docs/rig-limits.md "Fuzzing"): the fuzz targets' bodies, a library in every
# build (tests/fuzz runs tools/fuzz/corpus/ through them), and with -DMETROSYNC_FUZZ=ON (clang,
# build-fuzz: tools/setup.sh fuzz) libFuzzer's executables fuzz_<target>, one per body.
add_library(metrosync_tools_fuzz STATIC ${CMAKE_SOURCE_DIR}/tools/fuzz/fuzz_entries.cpp)
target_include_directories(metrosync_tools_fuzz PUBLIC ${CMAKE_SOURCE_DIR})
# metrosync_animate: the animate command (tools/report/animation.cmake), its options among all
target_link_libraries(metrosync_tools_fuzz PUBLIC metrosync_tools_cli metrosync_animate)
metrosync_simbody_flags(metrosync_tools_fuzz)
if(TARGET test_fuzz)
  target_link_libraries(test_fuzz PRIVATE metrosync_tools_fuzz)
endif()
if(METROSYNC_FUZZ)
  set(METROSYNC_FUZZ_TARGETS rig network keys data options)
  foreach(t ${METROSYNC_FUZZ_TARGETS})
    add_executable(fuzz_${t} ${CMAKE_SOURCE_DIR}/tools/fuzz/fuzz_target.cpp)
    target_compile_definitions(fuzz_${t} PRIVATE METROSYNC_FUZZ_TARGET="${t}")
    target_link_libraries(fuzz_${t} PRIVATE metrosync_tools_fuzz)
    target_link_options(fuzz_${t} PRIVATE -fsanitize=fuzzer)
  endforeach()
  add_custom_target(fuzz_targets)
  list(TRANSFORM METROSYNC_FUZZ_TARGETS PREPEND fuzz_ OUTPUT_VARIABLE _fuzz_exes)
  add_dependencies(fuzz_targets ${_fuzz_exes})
endif()
