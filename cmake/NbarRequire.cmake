# Dependencies that fail the configure step with the Debian package to install, instead of
# CMake's generic "could not find a package configuration file": a wheel or a .deb built on a
# machine without one stops here, never at import or at run time. scripts/install-deps.sh
# installs what the build needs (with --tests, what the tests and benchmarks need too).
#   nbar_require(<package> DEBIAN <debian-package> [find_package arguments...])
#   nbar_require_pkg_config(<prefix> <module> DEBIAN <debian-package>)
macro(nbar_require package)
  cmake_parse_arguments(_nbar_require "" "DEBIAN" "" ${ARGN})
  find_package(${package} ${_nbar_require_UNPARSED_ARGUMENTS} QUIET)
  if(NOT ${package}_FOUND)
    message(FATAL_ERROR "nbar needs ${package}: apt-get install ${_nbar_require_DEBIAN}")
  endif()
endmacro()

macro(nbar_require_pkg_config prefix module)
  cmake_parse_arguments(_nbar_require "GLOBAL" "DEBIAN" "" ${ARGN})
  set(_nbar_require_global "")
  if(_nbar_require_GLOBAL)
    set(_nbar_require_global GLOBAL)
  endif()
  pkg_check_modules(${prefix} QUIET IMPORTED_TARGET ${_nbar_require_global} ${module})
  if(NOT ${prefix}_FOUND)
    message(FATAL_ERROR "nbar needs ${module} (pkg-config): apt-get install ${_nbar_require_DEBIAN}")
  endif()
endmacro()
