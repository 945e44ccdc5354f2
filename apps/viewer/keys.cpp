// keys.cpp - the viewer's key bindings, as the source documents' demos name their switches.
#include "keys.hpp"

#include <cstddef>

#include "facet/names.hpp"

namespace facet::viewer {

const char* const kHelpText =
    "w  wireframe            e  edges over surfaces\n"
    "c  culling: back, front, none\n"
    "z  depth test on/off    p  painter's algorithm\n"
    "s  shuffle the triangle order\n"
    "m  colour map: by height, by intensity (scans), or the model's own colours\n"
    "1-7  unlit, flat, gouraud, phong, blinn-phong, normals, depth\n"
    "0  automatic: the model's own shading\n"
    "o  orthographic/perspective\n"
    "a  anti-aliasing (4x multisampling)\n"
    "r  reset the camera     space  pause\n"
    ",  .  step the animation a frame back, forward\n"
    "h  this help            q, Esc  quit\n"
    "mouse: left-drag orbits, right- or shift-drag pans, wheel zooms\n"
    "drop a model file on the window to open it";

KeyAction apply_key(char key, Toggles& t, Orbit& orbit, const Showing* showing) {
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
    case 'm': {  // the next of the library's colour maps that can be drawn, back to none after the last
      const auto maps = color_map_names();
      std::size_t k = 0;
      while (k < maps.size() && maps[k].value != t.color_map) ++k;
      do {
        k = (k + 1) % maps.size();
      } while (showing && !showing->supports(maps[k].value));
      t.color_map = maps[k].value;
      break;
    }
    case '0': t.shading.reset(); break;
    case 'o': t.orthographic = !t.orthographic; break;
    case 'a': t.antialias = !t.antialias; break;
    case ' ': t.paused = !t.paused; break;
    case ',':
    case '.':
      t.paused = true;
      t.steps += key == '.' ? 1 : -1;
      break;
    case 'h': t.help = !t.help; break;
    case 'r': orbit = Orbit{}; return KeyAction::reset_camera;
    case 'q':
    case '\x1b': return KeyAction::quit;
    default:
      // Keys 1-7 take the library's shadings in its order, after "automatic" (key 0).
      if (key >= '1' && key <= '7') {
        t.shading = shading_names()[static_cast<std::size_t>(key - '0')].value;
        break;
      }
      return KeyAction::unknown;
  }
  return KeyAction::none;
}

std::string describe(const Toggles& t) {
  std::string s = std::string("shading ") + name_of(shading_names(), t.shading.value_or(Shading::automatic));
  if (t.wireframe) s += ", wireframe";
  if (t.edges) s += ", edges";
  if (t.cull) s += std::string(", culling ") + name_of(cull_mode_names(), *t.cull);
  if (!t.depth_test) s += ", no depth test";
  if (t.painter) s += ", painter";
  if (t.shuffles) s += ", shuffled";
  if (t.color_map != ColorMap::none) s += std::string(", colour map ") + name_of(color_map_names(), t.color_map);
  if (t.orthographic) s += ", orthographic";
  if (t.antialias) s += ", anti-aliased";
  if (t.paused) s += ", paused";
  return s;
}

}  // namespace facet::viewer
