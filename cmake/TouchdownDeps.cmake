# The external dependencies of touchdown, listed once. The build includes this file to find them,
# and it is installed beside touchdownConfig.cmake, which includes it so that find_package(touchdown)
# finds them again on the machine that uses the package, wherever they live there. Each dependency
# is an imported target (CMake's own where a Find module makes one: GSL::gsl, HDF5::HDF5), listed in
# TD_DEPENDENCY_TARGETS; the exported touchdown targets name these targets, never a path found on
# the machine that built touchdown.
# A dependency that is missing stops the build, naming the Debian package to install; in a package
# configuration (find_package(touchdown)) it makes touchdown_FOUND false with that message instead.

macro(td_require found what package)
  if(NOT ${found})
    if(CMAKE_FIND_PACKAGE_NAME)
      set(${CMAKE_FIND_PACKAGE_NAME}_FOUND FALSE)
      set(${CMAKE_FIND_PACKAGE_NAME}_NOT_FOUND_MESSAGE
          "${CMAKE_FIND_PACKAGE_NAME} needs ${what}, which was not found (Debian: apt-get install ${package})")
      return()
    endif()
    message(FATAL_ERROR "touchdown: ${what} not found. On Debian 12 install it with:\n"
                        "    apt-get install ${package}\n"
                        "(or run scripts/setup.sh, which installs every dependency)")
  endif()
endmacro()

# td_dependency(<name> INCLUDE <dirs> LINK <libraries or targets>): the imported target
# touchdown_deps::<name> for a dependency that comes with no target of its own.
function(td_dependency name)
  cmake_parse_arguments(arg "" "" "INCLUDE;LINK" ${ARGN})
  if(NOT TARGET touchdown_deps::${name})
    add_library(touchdown_deps::${name} INTERFACE IMPORTED)
    set_target_properties(touchdown_deps::${name} PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${arg_INCLUDE}" INTERFACE_LINK_LIBRARIES "${arg_LINK}")
  endif()
endfunction()

# SUNDIALS IDA 6.x with KLU: found by library name; SUNDIALS's own CMake package drags in
# optional back ends (PETSc, hypre) that a Debian install may not have.
find_path(SUNDIALS_INCLUDE_DIR ida/ida.h)
td_require(SUNDIALS_INCLUDE_DIR "SUNDIALS IDA headers" libsundials-dev)
set(TD_SUNDIALS_LIBS)
foreach(lib sundials_ida sundials_nvecserial sundials_sunlinsolklu sundials_sunmatrixsparse
            sundials_sunlinsoldense sundials_sunmatrixdense)
  find_library(TD_LIB_${lib} ${lib})
  td_require(TD_LIB_${lib} "SUNDIALS library ${lib}" libsundials-dev)
  list(APPEND TD_SUNDIALS_LIBS ${TD_LIB_${lib}})
endforeach()
file(STRINGS ${SUNDIALS_INCLUDE_DIR}/sundials/sundials_config.h TD_SUNDIALS_VERSION_LINE
     REGEX "#define SUNDIALS_VERSION_MAJOR")
string(REGEX MATCH "[0-9]+" TD_SUNDIALS_MAJOR "${TD_SUNDIALS_VERSION_LINE}")
if(TD_SUNDIALS_MAJOR LESS 6)
  set(TD_SUNDIALS_6 FALSE)
  td_require(TD_SUNDIALS_6 "SUNDIALS 6.x or 7.x (found ${TD_SUNDIALS_MAJOR}.x)" libsundials-dev)
endif()
td_dependency(sundials INCLUDE ${SUNDIALS_INCLUDE_DIR} LINK ${TD_SUNDIALS_LIBS})

# SuiteSparse: KLU (sparse LU for IDA) and CXSparse (assembly of the sparse matrices). Debian 12's
# SuiteSparse 5 ships neither a CMake package nor a pkg-config module.
find_path(KLU_INCLUDE_DIR klu.h PATH_SUFFIXES suitesparse)
find_library(KLU_LIBRARY klu)
find_library(CXSPARSE_LIBRARY cxsparse)
td_require(KLU_INCLUDE_DIR "SuiteSparse KLU header klu.h" libsuitesparse-dev)
td_require(KLU_LIBRARY "SuiteSparse KLU library" libsuitesparse-dev)
td_require(CXSPARSE_LIBRARY "SuiteSparse CXSparse library" libsuitesparse-dev)
get_filename_component(TD_SUITESPARSE_PARENT ${KLU_INCLUDE_DIR} DIRECTORY)
td_dependency(suitesparse INCLUDE ${KLU_INCLUDE_DIR} ${TD_SUITESPARSE_PARENT}
                           LINK ${KLU_LIBRARY} ${CXSPARSE_LIBRARY})

find_package(GSL QUIET)
td_require(GSL_FOUND "GSL (GNU Scientific Library)" libgsl-dev)

# HL: the dimension-scale API (H5DS) that names the time, node and retainer axes for netCDF readers.
# FindHDF5 (CMake 3.19 and later) makes hdf5::hdf5_hl, which does not link the core library, and
# HDF5::HDF5: the core library with what it links (zlib, szip, curl...), which a static libhdf5.a
# needs and hdf5::hdf5 (the bare library) leaves out.
find_package(HDF5 QUIET COMPONENTS C HL)
td_require(HDF5_FOUND "HDF5 C and high-level libraries" libhdf5-dev)
set(TD_HDF5_LIBS ${HDF5_C_HL_LIBRARIES} ${HDF5_HL_LIBRARIES} ${HDF5_C_LIBRARIES})
list(REMOVE_DUPLICATES TD_HDF5_LIBS)

find_path(LIBCONFIG_INCLUDE_DIR libconfig.h)
find_library(LIBCONFIG_LIBRARY config)
td_require(LIBCONFIG_INCLUDE_DIR "libconfig header libconfig.h" libconfig-dev)
td_require(LIBCONFIG_LIBRARY "libconfig library" libconfig-dev)
td_dependency(libconfig INCLUDE ${LIBCONFIG_INCLUDE_DIR} LINK ${LIBCONFIG_LIBRARY})

# SLICOT 5.0 (GPL-2+, compatible with GSL's GPL-3): the control-system numerics of lib/control
# (bilinear map, matrix exponential and its integral, minimal realisation, balancing). A Fortran
# library without a C header (lib/control/slicot.h declares what is used) nor a pkg-config module.
# Only libslicot itself is linked, never LAPACK or BLAS: its shared library loads them as its own
# dependencies, after GSL's CBLAS (libgsl's own dependency) in the loader's breadth-first order. The
# system's libblas.so.3 (OpenBLAS, say) also exports the CBLAS symbols, and linked directly it came
# first and took GSL's BLAS calls, which changed the arithmetic of every shipped case
# (tests/link/cblas_order.sh checks the order).
find_library(SLICOT_LIBRARY slicot)
td_require(SLICOT_LIBRARY "SLICOT library" libslicot-dev)
td_dependency(slicot LINK ${SLICOT_LIBRARY})

set(TD_DEPENDENCY_TARGETS touchdown_deps::sundials touchdown_deps::suitesparse GSL::gsl
                          hdf5::hdf5_hl HDF5::HDF5 touchdown_deps::libconfig touchdown_deps::slicot)
