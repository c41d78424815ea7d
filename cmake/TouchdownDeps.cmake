# Finds every external dependency and stops with the Debian package to install when one is missing.
# All of them are gathered behind one interface target, td::deps.

function(td_require found what package)
  if(NOT ${found})
    message(FATAL_ERROR "touchdown: ${what} not found. On Debian 12 install it with:\n"
                        "    apt-get install ${package}\n"
                        "(or run scripts/setup.sh, which installs every dependency)")
  endif()
endfunction()

find_package(PkgConfig QUIET)

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
  message(FATAL_ERROR "touchdown: SUNDIALS ${TD_SUNDIALS_MAJOR}.x found, 6.x or 7.x needed (apt-get install libsundials-dev)")
endif()

# SuiteSparse: KLU (sparse LU for IDA) and CXSparse (assembly of the sparse matrices).
find_path(KLU_INCLUDE_DIR klu.h PATH_SUFFIXES suitesparse)
find_library(KLU_LIBRARY klu)
find_library(CXSPARSE_LIBRARY cxsparse)
td_require(KLU_INCLUDE_DIR "SuiteSparse KLU header klu.h" libsuitesparse-dev)
td_require(KLU_LIBRARY "SuiteSparse KLU library" libsuitesparse-dev)
td_require(CXSPARSE_LIBRARY "SuiteSparse CXSparse library" libsuitesparse-dev)
get_filename_component(TD_SUITESPARSE_PARENT ${KLU_INCLUDE_DIR} DIRECTORY)

find_package(GSL QUIET)
td_require(GSL_FOUND "GSL (GNU Scientific Library)" libgsl-dev)

# HL: the dimension-scale API (H5DS) that names the time, node and retainer axes for netCDF readers.
find_package(HDF5 QUIET COMPONENTS C HL)
td_require(HDF5_FOUND "HDF5 C and high-level libraries" libhdf5-dev)
set(TD_HDF5_LIBS ${HDF5_C_HL_LIBRARIES} ${HDF5_HL_LIBRARIES} ${HDF5_C_LIBRARIES})
list(REMOVE_DUPLICATES TD_HDF5_LIBS)

find_path(LIBCONFIG_INCLUDE_DIR libconfig.h)
find_library(LIBCONFIG_LIBRARY config)
td_require(LIBCONFIG_INCLUDE_DIR "libconfig header libconfig.h" libconfig-dev)
td_require(LIBCONFIG_LIBRARY "libconfig library" libconfig-dev)

find_program(GNUPLOT_EXECUTABLE gnuplot)
if(NOT GNUPLOT_EXECUTABLE)
  message(WARNING "touchdown: gnuplot not found; 'touchdown plot' needs it (apt-get install gnuplot-nox)")
endif()

add_library(td_deps INTERFACE)
add_library(td::deps ALIAS td_deps)
target_include_directories(td_deps INTERFACE
  ${SUNDIALS_INCLUDE_DIR} ${KLU_INCLUDE_DIR} ${TD_SUITESPARSE_PARENT} ${GSL_INCLUDE_DIRS}
  ${HDF5_C_INCLUDE_DIRS} ${HDF5_INCLUDE_DIRS} ${LIBCONFIG_INCLUDE_DIR})
target_compile_definitions(td_deps INTERFACE ${HDF5_C_DEFINITIONS} ${HDF5_DEFINITIONS})
target_link_libraries(td_deps INTERFACE ${TD_SUNDIALS_LIBS} ${KLU_LIBRARY} ${CXSPARSE_LIBRARY}
  ${GSL_LIBRARIES} ${TD_HDF5_LIBS} ${LIBCONFIG_LIBRARY} m)
