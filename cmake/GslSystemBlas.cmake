# GSL calls CBLAS (cblas_dnrm2, cblas_dgemv, cblas_dsyrk: 47 % of a 1 000-point
# Burgers fit with GSL's own reference CBLAS, libgslcblas). Where the system BLAS
# has the CBLAS interface (Debian: libblas.so.3, chosen at run time by
# update-alternatives; scripts/install-deps.sh installs OpenBLAS for it), GSL::gsl
# is linked to it instead of libgslcblas. Included by the top-level CMakeLists.txt
# and by the installed rheodda package (rheoddaConfig.cmake) after GSL is found.
include_guard(GLOBAL)
find_package(BLAS QUIET)
if(TARGET GSL::gsl AND BLAS_FOUND)
  include(CheckFunctionExists)
  set(_rheodda_saved_libs "${CMAKE_REQUIRED_LIBRARIES}")
  set(CMAKE_REQUIRED_LIBRARIES ${BLAS_LIBRARIES})
  set(CMAKE_REQUIRED_QUIET ON)
  check_function_exists(cblas_dnrm2 RHEODDA_BLAS_HAS_CBLAS)
  set(CMAKE_REQUIRED_LIBRARIES "${_rheodda_saved_libs}")
  if(RHEODDA_BLAS_HAS_CBLAS)
    set_property(TARGET GSL::gsl PROPERTY INTERFACE_LINK_LIBRARIES BLAS::BLAS)
  endif()
endif()
