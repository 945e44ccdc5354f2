// sdl.hpp - SDL2's functions the viewer calls, from libSDL2 opened when the first window opens.
#pragma once

#include <SDL.h>

namespace facet::viewer {

// SDL2 with its X11, Wayland and audio libraries is fifty shared objects; linked into the facet program they would
// slow the start of every `facet render` by about 15 ms. `facet view` opens it instead.
// clang-format off
#define FACET_SDL_FUNCTIONS(X) \
  X(SDL_ConvertPixels) X(SDL_CreateWindow) X(SDL_DestroyWindow) X(SDL_EventState) X(SDL_GetError) \
  X(SDL_GetModState) X(SDL_GetWindowSize) X(SDL_GetWindowSurface) X(SDL_Init) X(SDL_LockSurface) \
  X(SDL_PollEvent) X(SDL_Quit) X(SDL_SetHint) X(SDL_SetWindowTitle) X(SDL_UnlockSurface) \
  X(SDL_UpdateWindowSurface) X(SDL_WaitEventTimeout) X(SDL_free)
// clang-format on

struct Sdl {
#define FACET_DECLARE(name) decltype(&::name) name = nullptr;
  FACET_SDL_FUNCTIONS(FACET_DECLARE)
#undef FACET_DECLARE
};

// The table, filled on first use from libSDL2-2.0.so.0. Throws std::runtime_error naming the library and the
// Debian package when SDL2 is not installed; a later call tries again.
const Sdl& sdl();

}  // namespace facet::viewer
