# The private dependencies of touchdown.pc, for linking the static library (pkg-config --static).
# A dependency that ships a pkg-config module is named in Requires.private, so that its own .pc
# says where it lives; the others go into Libs.private as -l flags, with a -L only for a directory
# the compiler does not search anyway. No absolute library path goes into the file: a .pc written on
# one distribution then still reads right on another, and for an install into a moved prefix.
# Sets TD_PC_REQUIRES_PRIVATE and TD_PC_LIBS_PRIVATE (space-separated) for cmake/touchdown.pc.in.

find_package(PkgConfig QUIET)

# td_pc_module(<out> <found library> <module>...): the first module whose libraries include the
# one found, else "". Only such a module may stand for it: Debian's hdf5.pc, for one, may point at
# the MPI build of HDF5 while the serial one was found.
function(td_pc_module out found)
  set(${out} "" PARENT_SCOPE)
  if(NOT PKG_CONFIG_FOUND)
    return()
  endif()
  get_filename_component(found_real "${found}" REALPATH)
  foreach(module ${ARGN})
    string(MAKE_C_IDENTIFIER "td_pc_${module}" prefix)
    pkg_check_modules(${prefix} QUIET ${module})
    foreach(lib ${${prefix}_LINK_LIBRARIES})
      get_filename_component(lib_real "${lib}" REALPATH)
      if(lib_real STREQUAL found_real)
        set(${out} ${module} PARENT_SCOPE)
        set(td_pc_dirs ${td_pc_dirs} ${${prefix}_LIBRARY_DIRS} PARENT_SCOPE)
        return()
      endif()
    endforeach()
  endforeach()
endfunction()

# td_pc_flags(<out> <library>...): -l flags for libraries given as paths, names or flags; a -L for
# a directory neither the compiler nor a required module (td_pc_dirs) already searches.
function(td_pc_flags out)
  set(flags)
  foreach(lib ${ARGN})
    get_filename_component(name "${lib}" NAME)
    if(lib MATCHES "^-")
      list(APPEND flags ${lib})
    elseif(IS_ABSOLUTE "${lib}" AND name MATCHES "^lib(.+)\\.(so|a|dylib)(\\.[0-9.]+)?$")
      set(lname ${CMAKE_MATCH_1})
      get_filename_component(dir "${lib}" DIRECTORY)
      if(NOT dir IN_LIST CMAKE_C_IMPLICIT_LINK_DIRECTORIES AND NOT dir IN_LIST td_pc_dirs)
        list(APPEND flags -L${dir})
      endif()
      list(APPEND flags -l${lname})
    elseif(IS_ABSOLUTE "${lib}")
      list(APPEND flags ${lib})
    else()
      list(APPEND flags -l${lib})
    endif()
  endforeach()
  list(REMOVE_DUPLICATES flags)
  set(${out} ${flags} PARENT_SCOPE)
endfunction()

set(td_pc_dirs)
set(td_pc_requires)
set(td_pc_libs ${TD_SUNDIALS_LIBS} ${KLU_LIBRARY} ${CXSPARSE_LIBRARY})
td_pc_module(td_gsl_module "${GSL_LIBRARY}" gsl)
if(td_gsl_module)
  list(APPEND td_pc_requires ${td_gsl_module})
else()
  list(APPEND td_pc_libs ${GSL_LIBRARIES})
endif()
# HDF5's modules list the core library only: the high-level one (H5DS) stays a -l flag beside it,
# found in the same directory.
td_pc_module(td_hdf5_module "${HDF5_C_LIBRARY_hdf5}" hdf5-serial hdf5)
if(td_hdf5_module)
  list(APPEND td_pc_requires ${td_hdf5_module})
  list(APPEND td_pc_libs ${HDF5_C_HL_LIBRARIES} ${HDF5_HL_LIBRARIES})
else()
  list(APPEND td_pc_libs ${TD_HDF5_LIBS})
endif()
td_pc_module(td_libconfig_module "${LIBCONFIG_LIBRARY}" libconfig)
if(td_libconfig_module)
  list(APPEND td_pc_requires ${td_libconfig_module})
else()
  list(APPEND td_pc_libs ${LIBCONFIG_LIBRARY})
endif()
list(APPEND td_pc_libs ${SLICOT_LIBRARY}) # not LAPACK, BLAS: see TouchdownDeps.cmake
td_pc_flags(td_pc_lib_flags ${td_pc_libs} m)
string(JOIN " " TD_PC_REQUIRES_PRIVATE ${td_pc_requires})
string(JOIN " " TD_PC_LIBS_PRIVATE ${td_pc_lib_flags})
message(STATUS "touchdown.pc: Requires.private: ${TD_PC_REQUIRES_PRIVATE}")
