# The Debian packages, made by CPack from what `cmake --install` puts in place (scripts/package.sh
# runs `cpack -G DEB` in a build directory):
#   nbar_<version>_amd64.deb         component "runtime": the program, its man page and bash
#                                    completion, the Python module for Debian's python3, the
#                                    manual, the examples and the notebooks
#   libnbar-dev_<version>_amd64.deb  component "development": the static libraries, their headers
#                                    and the CMake package, for find_package(nbar) from /usr
# Two packages, as Debian splits a library: nbar's static libraries need the -dev packages of
# what they link (cairo's alone brings the X11 headers), which a user of the program should not
# have to install.

# The manual and the examples, where Debian keeps a package's documentation. The notebooks load
# the copy inside the Python package (nbar.examples), so that they run wherever they are copied.
set(NBAR_DOC_DIR ${CMAKE_INSTALL_DATADIR}/doc/nbar)
install(FILES README.md CHANGELOG.md DESTINATION ${NBAR_DOC_DIR} COMPONENT runtime)
install(FILES LICENSE DESTINATION ${NBAR_DOC_DIR} RENAME copyright COMPONENT runtime)
install(DIRECTORY docs/ DESTINATION ${NBAR_DOC_DIR}/docs COMPONENT runtime)
install(DIRECTORY notebooks/ DESTINATION ${NBAR_DOC_DIR}/notebooks COMPONENT runtime)
# examples/cpp/CMakeLists.txt builds the C++ examples inside this tree only; analyse-model is a
# project of its own, built against the installed package.
install(DIRECTORY examples/ DESTINATION ${NBAR_DOC_DIR}/examples COMPONENT runtime
        PATTERN "cpp/CMakeLists.txt" EXCLUDE)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME nbar)
set(CPACK_PACKAGE_VENDOR "the nbar authors")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "analysis, simulation and synthesis of planar linkages")
set(CPACK_PACKAGE_DESCRIPTION
    "nbar assembles planar linkages (four-bars, slider-cranks, six-bars, engines) from a YAML file, follows the\n"
    "drawn assembly branch over a sweep and gives positions, velocities, accelerations, joint forces, motor\n"
    "torques and link stresses; it draws and animates mechanisms and designs four-bars.")
string(REPLACE ";" "" CPACK_PACKAGE_DESCRIPTION "${CPACK_PACKAGE_DESCRIPTION}")
set(CPACK_PACKAGE_CONTACT "the nbar authors")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGE_DIRECTORY ${PROJECT_BINARY_DIR}/packages)
set(CPACK_STRIP_FILES ON)  # the program and the Python module; static libraries are never stripped

set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL runtime development)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME nbar)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SECTION science)
# dpkg-shlibdeps adds the shared libraries the program and the module link (yaml-cpp, fmt,
# cairo, cgif, cpp-httplib, libstdc++...); the module is for Debian's python3 (the .so is built
# for 3.11) and imports numpy.
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_DEPENDS "python3 (>= 3.11), python3 (<< 3.12), python3-numpy")
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SUGGESTS "python3-matplotlib, python3-pandas, ffmpeg, libnbar-dev")
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_NAME libnbar-dev)
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_SECTION libdevel)
# What nbarConfig.cmake finds: Eigen for the headers, the rest for what the static libraries link.
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_DEPENDS
    "libeigen3-dev (>= 3.4), libyaml-cpp-dev, libfmt-dev, libcairo2-dev, libcgif-dev, pkg-config")
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_SUGGESTS "cmake, g++")
include(CPack)
