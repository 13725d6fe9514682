# Docs that run (issue 37): one test per Markdown file of README.md and docs/, labelled `docs`,
# each running the file's commands with their exit codes checked (tests/docs/run_docs.py; the
# shortenings and the commands that cannot run, with the reason, in tests/docs/shortenings.py).
# New pages are picked up at the next build (the glob is re-checked); new commands in a page at
# once (the page is read when its test runs). With `docs:table` (every entry of the table still
# matches a command) and `docs:pointers` (no user-facing text points outside the repository).
if(NOT GTest_FOUND)
  return()  # a `run`-only configuration (tools/setup.sh): no tests
endif()
set(_docs_python ${Python_EXECUTABLE})
if(NOT _docs_python)
  find_program(_docs_python python3)
endif()
file(GLOB_RECURSE _docs_pages CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/docs/*.md)
set(_docs_script ${CMAKE_SOURCE_DIR}/tests/docs/run_docs.py)
foreach(page ${CMAKE_SOURCE_DIR}/README.md ${_docs_pages})
  file(RELATIVE_PATH rel ${CMAKE_SOURCE_DIR} ${page})
  add_test(NAME docs:${rel}
           COMMAND ${_docs_python} ${_docs_script} commands ${rel} --source ${CMAKE_SOURCE_DIR}
                   --build ${CMAKE_BINARY_DIR})
  set_tests_properties(docs:${rel} PROPERTIES LABELS docs TIMEOUT 900)
endforeach()
add_test(NAME docs:table COMMAND ${_docs_python} ${_docs_script} table --source ${CMAKE_SOURCE_DIR})
add_test(NAME docs:pointers
         COMMAND ${_docs_python} ${_docs_script} pointers --source ${CMAKE_SOURCE_DIR}
                 --build ${CMAKE_BINARY_DIR})
set_tests_properties(docs:table docs:pointers PROPERTIES LABELS docs TIMEOUT 300)
