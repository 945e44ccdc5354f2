// keys.hpp - the viewer's keys: what each one flips, and the help text that lists them.
#pragma once

#include <string>

#include "viewer_state.hpp"

namespace facet::viewer {

// What a key asks the viewer to do beyond flipping a toggle.
enum class KeyAction { none, unknown, quit, reset_camera };

// Applies one key (a character as typed: 'w', '1', ' ', 'q'; Esc is '\x1b') to the toggles and orbit. The colour
// map key skips the maps `showing` cannot draw, when given.
KeyAction apply_key(char key, Toggles& toggles, Orbit& orbit, const Showing* showing = nullptr);

// The keys and mouse buttons, one per line, for the on-screen help and `facet view --help`.
extern const char* const kHelpText;

// The toggles in a few words, for the window title: "phong, wireframe, cull back, no depth test".
std::string describe(const Toggles& toggles);

}  // namespace facet::viewer
