# standalone.cmake - what the builds outside the main CMakeLists.txt (the browser page's, web/, and the portable
# one, tests/portable/) set alike: C++20 without extensions, a release build unless told otherwise, and ccache
# when it is installed.
set(CMAKE_CXX_STANDARD 20)
set(CMAKE_CXX_STANDARD_REQUIRED ON)
set(CMAKE_CXX_EXTENSIONS OFF)
if(NOT CMAKE_BUILD_TYPE)
  set(CMAKE_BUILD_TYPE Release)
endif()
find_program(FACET_CCACHE_PROGRAM ccache)
if(FACET_CCACHE_PROGRAM AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
  set(CMAKE_CXX_COMPILER_LAUNCHER ${FACET_CCACHE_PROGRAM})
  set(CMAKE_C_COMPILER_LAUNCHER ${FACET_CCACHE_PROGRAM})
endif()
