// sdl.cpp - opens libSDL2 and looks up the viewer's functions once.
#include "viewer/sdl.hpp"

#include "job/shared_library.hpp"

namespace facet::viewer {

const Sdl& sdl() {
  static const Sdl table = [] {
    const SharedLibrary library("libSDL2-2.0.so.0", "libsdl2-2.0-0");
    Sdl s;
#define FACET_RESOLVE(name) s.name = library.function<decltype(&::name)>(#name);
    FACET_SDL_FUNCTIONS(FACET_RESOLVE)
#undef FACET_RESOLVE
    return s;
  }();
  return table;
}

}  // namespace facet::viewer
