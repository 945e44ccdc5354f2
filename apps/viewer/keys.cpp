// keys.cpp - the viewer's key bindings, as the source documents' demos name their switches.
#include "keys.hpp"

namespace facet::viewer {

const char* const kHelpText =
    "w  wireframe            e  edges over surfaces\n"
    "c  culling: back, front, none\n"
    "z  depth test on/off    p  painter's algorithm\n"
    "s  shuffle the triangle order\n"
    "1-7  unlit, flat, Gouraud, Phong, Blinn-Phong, normals, depth\n"
    "0  the model's own shading\n"
    "o  orthographic/perspective\n"
    "a  anti-aliasing (4x multisampling)\n"
    "r  reset the camera     space  pause\n"
    "h  this help            q, Esc  quit\n"
    "mouse: left-drag orbits, right- or shift-drag pans, wheel zooms\n"
    "drop a model file on the window to open it";

KeyAction apply_key(char key, Toggles& t, Orbit& orbit) {
  static constexpr Shading kShadings[] = {Shading::unlit,       Shading::flat,    Shading::gouraud, Shading::phong,
                                          Shading::blinn_phong, Shading::normals, Shading::depth};
  switch (key) {
    case 'w': t.wireframe = !t.wireframe; break;
    case 'e': t.edges = !t.edges; break;
    case 'c':
      if (!t.cull || *t.cull == CullMode::none) t.cull = CullMode::back;
      else if (*t.cull == CullMode::back) t.cull = CullMode::front;
      else t.cull = CullMode::none;
      break;
    case 'z': t.depth_test = !t.depth_test; break;
    case 'p': t.painter = !t.painter; break;
    case 's': ++t.shuffles; break;
    case '0': t.shading.reset(); break;
    case 'o': t.orthographic = !t.orthographic; break;
    case 'a': t.antialias = !t.antialias; break;
    case ' ': t.paused = !t.paused; break;
    case 'h': t.help = !t.help; break;
    case 'r': orbit = Orbit{}; return KeyAction::reset_camera;
    case 'q':
    case '\x1b': return KeyAction::quit;
    default:
      if (key >= '1' && key <= '7') {
        t.shading = kShadings[key - '1'];
        break;
      }
      return KeyAction::unknown;
  }
  return KeyAction::none;
}

std::string describe(const Toggles& t) {
  static constexpr const char* kNames[] = {"own shading", "unlit",       "flat",    "Gouraud",
                                           "Phong",       "Blinn-Phong", "normals", "depth"};
  std::string s = kNames[t.shading ? static_cast<int>(*t.shading) : 0];
  if (t.wireframe) s += ", wireframe";
  if (t.edges) s += ", edges";
  if (t.cull)
    s += *t.cull == CullMode::back ? ", cull back" : *t.cull == CullMode::front ? ", cull front" : ", no culling";
  if (!t.depth_test) s += ", no depth test";
  if (t.painter) s += ", painter";
  if (t.shuffles) s += ", shuffled";
  if (t.orthographic) s += ", orthographic";
  if (t.antialias) s += ", anti-aliased";
  if (t.paused) s += ", paused";
  return s;
}

}  // namespace facet::viewer
