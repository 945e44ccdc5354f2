// shared_library.hpp - system libraries opened when a feature first needs them, so starting facet never waits for them.
#pragma once

#include <string>

namespace facet {

// A shared library opened with dlopen by its soname. Large optional dependencies (FFmpeg for video, SDL2 for the
// viewer) pull in a hundred more libraries each; linking them would add tens of milliseconds to every `facet
// render`, which uses neither. Assimp, for the formats facet has no reader of its own, is one large C++ library
// whose relocations and constructors alone cost 5 ms. A library, once opened, stays loaded for the life of the
// process.
class SharedLibrary {
 public:
  // Opens soname (e.g. "libavcodec.so.59"). Throws std::runtime_error("cannot load <soname> (<package>): <why>")
  // when it is not installed, naming the Debian package that provides it.
  SharedLibrary(const std::string& soname, const std::string& package);

  // The address of a function in the library, as the pointer type F. Throws std::runtime_error naming the symbol
  // and the library when it is missing (a library of another version).
  template <class F>
  F function(const char* name) const {
    return reinterpret_cast<F>(symbol(name));
  }

 private:
  void* symbol(const char* name) const;

  std::string soname_;
  void* handle_ = nullptr;
};

}  // namespace facet
