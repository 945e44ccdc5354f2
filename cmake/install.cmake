# install.cmake - install rules: the library, its headers, the facet program, a CMake package and facet.pc.
# Components, which cmake/packaging.cmake maps to Debian packages: runtime (the program; the Python module is
# python/'s component python) and dev (everything a program built against facet needs).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS facet EXPORT facetTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev)
install(DIRECTORY include/facet DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT dev)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/include/facet/version.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/facet
        COMPONENT dev)
install(TARGETS facet_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
# The desktop's thumbnailer entry, and the model types Debian's MIME database lacks (its dpkg trigger, or
# update-mime-database, takes them in).
install(FILES data/facet.thumbnailer DESTINATION ${CMAKE_INSTALL_DATADIR}/thumbnailers COMPONENT runtime)
install(FILES data/facet-mime.xml DESTINATION ${CMAKE_INSTALL_DATADIR}/mime/packages RENAME facet.xml
        COMPONENT runtime)

set(FACET_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/facet)
install(EXPORT facetTargets NAMESPACE facet:: DESTINATION ${FACET_CMAKE_DIR} COMPONENT dev)
configure_package_config_file(cmake/facetConfig.cmake.in ${CMAKE_CURRENT_BINARY_DIR}/facetConfig.cmake
                              INSTALL_DESTINATION ${FACET_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/facetConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/facetConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/facetConfigVersion.cmake
        DESTINATION ${FACET_CMAKE_DIR} COMPONENT dev)

# facet is a static library, so facet.pc lists the libraries it uses in Libs: a plain `pkg-config --libs facet`
# links. The flags the templated stages need (see CMakeLists.txt) travel in Cflags.
# The prefix is found from the .pc file's own place, so the tree works wherever `cmake --install --prefix` puts it.
list(JOIN FACET_PUBLIC_FLAGS " " FACET_PC_FLAGS)
# Six libraries are named by file in Libs rather than as modules in Requires, in the order facet links them
# (CMakeLists.txt says why stb's archive precedes Draco's; pkg-config would put Requires after Libs): tinygltf,
# stb's archive, OpenEXR's C core (OpenEXR.pc names the C++ libraries too, which facet does not use), Draco's static
# archive (draco.pc names the shared library), meshoptimizer and liblzf (which ship no .pc file).
get_target_property(FACET_PC_TINYGLTF TinyGLTF::TinyGLTF LOCATION)
get_target_property(FACET_PC_EXR_CORE OpenEXR::OpenEXRCore LOCATION)
get_target_property(FACET_PC_DRACO draco::draco_static LOCATION)
get_target_property(FACET_PC_MESHOPT meshoptimizer::meshoptimizer LOCATION)
get_target_property(FACET_PC_LZF liblzf::liblzf LOCATION)
set(FACET_PC_LIBS "")
foreach(file ${FACET_PC_TINYGLTF} ${FACET_STB_ARCHIVE} ${FACET_PC_EXR_CORE} ${FACET_PC_DRACO} ${FACET_PC_MESHOPT}
        ${FACET_PC_LZF} ${FACET_ISAL_LIBRARY})
  get_filename_component(folder ${file} DIRECTORY)
  get_filename_component(file ${file} NAME)
  if(NOT folder IN_LIST CMAKE_CXX_IMPLICIT_LINK_DIRECTORIES)
    string(APPEND FACET_PC_LIBS " -L${folder}")
  endif()
  if(file MATCHES "^lib(.+)\\.so")
    string(APPEND FACET_PC_LIBS " -l${CMAKE_MATCH_1}")
  else()
    string(APPEND FACET_PC_LIBS " -l:${file}")
  endif()
endforeach()
string(STRIP "${FACET_PC_LIBS}" FACET_PC_LIBS)
file(RELATIVE_PATH FACET_PC_PREFIX_FROM_PCFILEDIR /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
configure_file(cmake/facet.pc.in ${CMAKE_CURRENT_BINARY_DIR}/facet.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/facet.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig COMPONENT dev)
