# FindSiconos: the Siconos kernel and numerics libraries (Debian: libsiconos-kernel-dev), for the
# benchmark's Moreau-Jean peer only.
#
# Why not Siconos's own siconos-config.cmake: Debian's libsiconos-kernel-dev ships the config of the
# whole Siconos build, whose target file stops configuration with a FATAL_ERROR when the control,
# mechanics and io libraries (other packages) are not installed; it also sets CMAKE_CXX_STANDARD 11.
# This module looks only for what the peer links and never fails the configuration.
#
# Call find_package(Boost) first: the kernel's headers include Boost (ublas, shared_ptr).
#
# Defines Siconos_FOUND, Siconos_INCLUDE_DIRS, Siconos_LIBRARIES and the imported target
# metrosync::siconos.
find_path(Siconos_INCLUDE_DIR NAMES siconos/kernel/SiconosKernel.hpp)
find_library(Siconos_KERNEL_LIBRARY NAMES siconos_kernel)
find_library(Siconos_NUMERICS_LIBRARY NAMES siconos_numerics)
find_library(Siconos_EXTERNALS_LIBRARY NAMES siconos_externals)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(Siconos
  REQUIRED_VARS Siconos_INCLUDE_DIR Siconos_KERNEL_LIBRARY Siconos_NUMERICS_LIBRARY
                Boost_FOUND)

if(Siconos_FOUND)
  set(Siconos_INCLUDE_DIRS ${Siconos_INCLUDE_DIR}/siconos ${Siconos_INCLUDE_DIR}/siconos/kernel
                           ${Siconos_INCLUDE_DIR}/siconos/numerics)
  set(Siconos_LIBRARIES ${Siconos_KERNEL_LIBRARY} ${Siconos_NUMERICS_LIBRARY})
  if(Siconos_EXTERNALS_LIBRARY)
    list(APPEND Siconos_LIBRARIES ${Siconos_EXTERNALS_LIBRARY})
  endif()
  if(NOT TARGET metrosync::siconos)
    add_library(metrosync::siconos INTERFACE IMPORTED)
    set_target_properties(metrosync::siconos PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${Siconos_INCLUDE_DIRS}"
      INTERFACE_LINK_LIBRARIES "${Siconos_LIBRARIES};Boost::boost")
  endif()
endif()
mark_as_advanced(Siconos_INCLUDE_DIR Siconos_KERNEL_LIBRARY Siconos_NUMERICS_LIBRARY
                 Siconos_EXTERNALS_LIBRARY)
