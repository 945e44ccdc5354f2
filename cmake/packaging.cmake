# packaging.cmake - CPack: the Debian packages facet (program, Python module) and facet-dev (library, headers).
# `cpack -G DEB` in the build folder makes them; scripts/deb_test.sh installs them into a clean Debian root.
# Included at the end of CMakeLists.txt: it looks at which targets (Python module, viewer) the build has.

# One package per group of install() components (cmake/install.cmake, python/CMakeLists.txt): the program and the
# Python module are what a user runs, so they travel together; dev is what a program built against facet needs.
set(CPACK_COMPONENTS_ALL runtime dev)
set(CPACK_COMPONENT_RUNTIME_GROUP runtime)
if(TARGET facet_python)
  list(APPEND CPACK_COMPONENTS_ALL python)
  set(CPACK_COMPONENT_PYTHON_GROUP runtime)
endif()
set(CPACK_GENERATOR DEB)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)

set(CPACK_PACKAGE_NAME facet)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "facet developers")
set(CPACK_PACKAGE_CONTACT "facet developers")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "facet developers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
# Each package's description below starts with its own synopsis: packaging_options.cmake, read by cpack, stops
# CPackDeb putting the project's summary before it.
set(CPACK_PROJECT_CONFIG_FILE ${CMAKE_CURRENT_LIST_DIR}/packaging_options.cmake)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
# Strips the program and the Python module, as Debian's own packages are; install(TARGETS) never strips an archive,
# so libfacet.a keeps the symbols that programs link against.
set(CPACK_STRIP_FILES ON)

# facet: the shared libraries the program and the module link come from dpkg-shlibdeps. Libraries that facet opens
# with dlopen only when a feature needs them (src/job/shared_library.hpp), by the soname of the version it was
# built against, are invisible to it: Assimp, which reads every model format facet has no reader of its own for, is
# recommended; FFmpeg (video output) and SDL2 (`facet view`'s window) are suggested, being large and desktop-bound.
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME facet)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_RUNTIME_DESCRIPTION "3D renderer on the CPU: command-line program and Python module
The facet program renders model files (glTF, OBJ, PLY, STL and the formats
Assimp reads) to PNG images, contact sheets, animations and depth, normal
and id buffers, with no GPU. The Python module facet drives the same
renderer from Python and returns its buffers as NumPy arrays.")
set(CPACK_DEBIAN_RUNTIME_PACKAGE_RECOMMENDS "libassimp${assimp_VERSION_MAJOR}")
set(facet_suggests "")
foreach(library avcodec avformat avutil swscale)
  string(REGEX MATCH "^[0-9]+" major "${ffmpeg_lib${library}_VERSION}")
  list(APPEND facet_suggests "lib${library}${major}")
endforeach()
if(TARGET facet_viewer)
  list(APPEND facet_suggests libsdl2-2.0-0)
endif()
list(JOIN facet_suggests ", " CPACK_DEBIAN_RUNTIME_PACKAGE_SUGGESTS)
if(TARGET facet_python)
  # The compiled core is built for one Python version (python/CMakeLists.txt), and the module imports numpy.
  string(REPLACE "." ";" python_version "${FACET_PYTHON_VERSION}")
  list(GET python_version 0 python_major)
  list(GET python_version 1 python_minor)
  math(EXPR python_next_minor "${python_minor} + 1")
  set(CPACK_DEBIAN_RUNTIME_PACKAGE_DEPENDS
      "python3 (>= ${FACET_PYTHON_VERSION}~), python3 (<< ${python_major}.${python_next_minor}), python3-numpy")
endif()

# facet-dev: the -dev packages of what facetConfig.cmake and facet.pc ask for (the libraries libfacet.a links,
# glm in the public headers, pkg-config for the modules that facetConfig.cmake looks up through it), and Assimp's
# run-time library, which programs built against facet open as the facet program does.
set(CPACK_DEBIAN_DEV_PACKAGE_NAME facet-dev)
set(CPACK_DEBIAN_DEV_DESCRIPTION "3D renderer on the CPU: C++ library and headers
The static library libfacet.a, its C++20 headers, the CMake package
facet::facet (find_package(facet)) and facet.pc for pkg-config, to build
programs that render with facet.")
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS
    "libglm-dev, libtinyobjloader-dev, libtinygltf-dev, libstb-dev, libopenexr-dev, libdraco-dev, \
libmeshoptimizer-dev, liblzf-dev, libisal-dev, zlib1g-dev, libgif-dev, libspng-dev, libturbojpeg0-dev, pkg-config")
set(CPACK_DEBIAN_DEV_PACKAGE_RECOMMENDS "libassimp${assimp_VERSION_MAJOR}")

include(CPack)

# The test (scripts/deb_test.sh): builds both packages, installs them with apt into a fresh bookworm root made by
# mmdebstrap and renders with them there. It needs root and Debian's mirror, and skips itself without root; its
# label lets `ctest -L package` run it alone and `ctest -LE package` leave it out.
if(FACET_BUILD_TESTS AND NOT FACET_SANITIZE AND NOT FACET_SANITIZE_THREAD AND NOT FACET_PROPERTY_TESTS_ONLY)
  add_test(NAME package.deb
           COMMAND bash ${PROJECT_SOURCE_DIR}/scripts/deb_test.sh ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR}
                   ${CMAKE_BINARY_DIR}/test-output/package/deb)
  set_tests_properties(package.deb PROPERTIES TIMEOUT 600 LABELS package SKIP_RETURN_CODE 77 COST 30)
endif()
