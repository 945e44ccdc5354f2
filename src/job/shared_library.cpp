// shared_library.cpp - dlopen and dlsym with errors that say which library and package are missing.
#include "job/shared_library.hpp"

#include <dlfcn.h>

#include <stdexcept>

namespace facet {

SharedLibrary::SharedLibrary(const std::string& soname, const std::string& package) : soname_(soname) {
  handle_ = ::dlopen(soname.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle_) {
    const char* why = ::dlerror();
    throw std::runtime_error("cannot load " + soname + " (Debian package " + package +
                             "): " + (why ? why : "unknown error"));
  }
}

void* SharedLibrary::symbol(const char* name) const {
  ::dlerror();
  void* address = ::dlsym(handle_, name);
  if (!address) throw std::runtime_error(soname_ + " has no function " + name + ": another version of the library?");
  return address;
}

}  // namespace facet
