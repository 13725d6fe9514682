# The Python module `metrosync` (docs/python.md), built when pybind11 and Debian's Python 3 are
# found: build/python/metrosync/ holds the package (its .py files copied, _metrosync compiled in),
# importable with PYTHONPATH=build/python; `cmake --install` puts it where
# Debian's python3 finds it (below).
# Debian's /usr/bin/python3 is preferred: the python3 first on PATH may be another interpreter
# without numpy (a pyenv one), and the module must match the interpreter that imports it.
if(EXISTS /usr/bin/python3 AND NOT Python_EXECUTABLE)
  set(Python_EXECUTABLE /usr/bin/python3)
endif()
find_package(Python COMPONENTS Interpreter Development.Module QUIET)
find_package(pybind11 CONFIG QUIET)
if(NOT (Python_FOUND AND pybind11_FOUND))
  message(STATUS "Python module: not built (needs pybind11-dev and python3-dev)")
  return()
endif()
set(METROSYNC_PYTHON_DIR ${CMAKE_BINARY_DIR}/python)
# NO_EXTRAS: no link-time optimization of the whole of metrosync into the module (minutes)
file(GLOB metrosync_python_cpp CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/tools/python/*.cpp)
pybind11_add_module(_metrosync NO_EXTRAS ${metrosync_python_cpp})
target_include_directories(_metrosync PRIVATE ${CMAKE_SOURCE_DIR})
target_link_libraries(_metrosync PRIVATE metrosync_tools_cli)
metrosync_link_heavy(_metrosync)
set_target_properties(_metrosync PROPERTIES LIBRARY_OUTPUT_DIRECTORY
                                            ${METROSYNC_PYTHON_DIR}/metrosync)
file(GLOB metrosync_py CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/tools/python/metrosync/*.py
     ${CMAKE_SOURCE_DIR}/tools/python/metrosync/*.pyi ${CMAKE_SOURCE_DIR}/tools/python/metrosync/py.typed)
foreach(f ${metrosync_py})
  get_filename_component(name ${f} NAME)
  configure_file(${f} ${METROSYNC_PYTHON_DIR}/metrosync/${name} COPYONLY)
endforeach()

# pytest (Debian python3-pytest) after the C++ tests: tests/python
add_test(NAME python_api
         COMMAND ${Python_EXECUTABLE} -m pytest -q -p no:cacheprovider ${CMAKE_SOURCE_DIR}/tests/python)
set_tests_properties(python_api PROPERTIES
  ENVIRONMENT "PYTHONPATH=${METROSYNC_PYTHON_DIR};METROSYNC_BINARY=$<TARGET_FILE:metrosync>;METROSYNC_SOURCE_DIR=${CMAKE_SOURCE_DIR}"
  LABELS slow TIMEOUT 900)

# The notebooks of docs/notebooks/ executed into build/notebooks/ (Debian jupyter-nbconvert,
# python3-ipykernel, python3-matplotlib, python3-pandas): a failing cell fails the test. Each runs
# in well under a minute (the notebooks say how long).
foreach(nb paper-figures classroom)
  string(REPLACE "-" "_" nb_test ${nb})
  add_test(NAME notebook_${nb_test}
           COMMAND ${Python_EXECUTABLE} -m nbconvert --to notebook --execute
                   --ExecutePreprocessor.timeout=300 --ExecutePreprocessor.kernel_name=python3
                   --output-dir ${CMAKE_BINARY_DIR}/notebooks
                   ${CMAKE_SOURCE_DIR}/docs/notebooks/${nb}.ipynb)
  set_tests_properties(notebook_${nb_test} PROPERTIES
    ENVIRONMENT "PYTHONPATH=${METROSYNC_PYTHON_DIR};METROSYNC_SOURCE_DIR=${CMAKE_SOURCE_DIR};PYDEVD_DISABLE_FILE_VALIDATION=1"
    LABELS slow TIMEOUT 600)
endforeach()

# Where the module goes under the prefix: Debian's python3 searches PREFIX/lib/python3.X/
# dist-packages for both /usr/local (`cmake --install`) and /usr (the package), but
# lib/python3/dist-packages only under /usr; elsewhere (no Debian scheme) site-packages.
execute_process(COMMAND ${Python_EXECUTABLE} -c [=[
import sys, sysconfig
local = "posix_local" in sysconfig.get_scheme_names()
scheme, base = ("posix_local", "/usr/local/") if local else ("posix_prefix", sys.prefix + "/")
path = sysconfig.get_path("platlib", scheme)
print(path[len(base):] if path.startswith(base) else "")
]=]
                OUTPUT_VARIABLE metrosync_site OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT metrosync_site)
  set(metrosync_site lib/python${Python_VERSION_MAJOR}.${Python_VERSION_MINOR}/site-packages)
endif()
install(TARGETS _metrosync LIBRARY DESTINATION ${metrosync_site}/metrosync)
# the Debian package (tools/install/install.cmake): the module is made for this Python's minor
# version and imports numpy; pandas only for to_pandas()
math(EXPR metrosync_next_minor "${Python_VERSION_MINOR} + 1")
set(METROSYNC_PYTHON_DEB_DEPENDS "python3 (>= ${Python_VERSION_MAJOR}.${Python_VERSION_MINOR}~), \
python3 (<< ${Python_VERSION_MAJOR}.${metrosync_next_minor}), python3-numpy")
set(METROSYNC_PYTHON_DEB_SUGGESTS "python3-pandas")
install(FILES ${metrosync_py} DESTINATION ${metrosync_site}/metrosync)

# `pip install .` and `pip wheel .` (setup.py, docs/python.md) into a fresh virtual environment,
# offline, the C++ core taken from this build tree: tests/pip.
add_test(NAME python_pip
         COMMAND ${Python_EXECUTABLE} -m pytest -q -p no:cacheprovider ${CMAKE_SOURCE_DIR}/tests/pip)
set_tests_properties(python_pip PROPERTIES
  ENVIRONMENT "METROSYNC_CMAKE_BUILD_DIR=${CMAKE_BINARY_DIR};METROSYNC_SOURCE_DIR=${CMAKE_SOURCE_DIR}"
  LABELS slow TIMEOUT 600)
