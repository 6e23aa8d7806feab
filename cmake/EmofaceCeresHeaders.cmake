# emoface_ceres_headers: Ceres Solver's header-only parts (ceres/tiny_solver.h, ceres/jet.h,
# ceres/tiny_solver_autodiff_function.h) without the compiled library. Debian's libceres links
# SuiteSparse CHOLMOD, whose Supernodal, MatrixOps and Modify modules are GPL-2+ (plus glog, gflags,
# CXSparse, BLAS/LAPACK); emoface's Ceres problems are small and dense, so it uses only these
# headers and links none of that (tests/licence/check_no_gpl_link.sh checks it).
#
# Libraries link it privately as $<BUILD_INTERFACE:emoface_ceres_headers>: it is not exported,
# and an installed emoface needs neither Ceres nor its dependencies.
if(NOT TARGET emoface_ceres_headers)
  find_package(Eigen3 3.3 REQUIRED NO_MODULE)
  # find_package(Ceres) only locates the headers (it is a required dependency of the project); the
  # imported target Ceres::ceres is never linked.
  find_package(Ceres 2.0 REQUIRED)
  get_target_property(_emoface_ceres_dirs Ceres::ceres INTERFACE_INCLUDE_DIRECTORIES)
  find_path(EMOFACE_CERES_INCLUDE_DIR NAMES ceres/tiny_solver.h ceres/jet.h
    HINTS ${_emoface_ceres_dirs} NO_CMAKE_FIND_ROOT_PATH)
  set(_emoface_autodiff "${EMOFACE_CERES_INCLUDE_DIR}/ceres/tiny_solver_autodiff_function.h")
  if(NOT EMOFACE_CERES_INCLUDE_DIR OR NOT EXISTS "${_emoface_autodiff}")
    message(FATAL_ERROR "emoface: Ceres' header-only solver (ceres/tiny_solver.h, "
      "ceres/tiny_solver_autodiff_function.h) not found; install libceres-dev (Ceres >= 2.0)")
  endif()
  add_library(emoface_ceres_headers INTERFACE)
  target_include_directories(emoface_ceres_headers SYSTEM INTERFACE ${EMOFACE_CERES_INCLUDE_DIR})
  target_link_libraries(emoface_ceres_headers INTERFACE Eigen3::Eigen)
  message(STATUS "emoface: Ceres ${Ceres_VERSION} header-only (TinySolver, Jet) from "
    "${EMOFACE_CERES_INCLUDE_DIR}")
endif()
