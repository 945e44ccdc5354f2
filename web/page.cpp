// page.cpp - the browser page's module: the viewer's demos, toggles and orbit, drawn by facet into canvas pixels.
#include <emscripten/emscripten.h>

#include <cstdint>
#include <exception>
#include <new>
#include <optional>
#include <string>

#include "facet/demo_scenes.hpp"
#include "facet/framebuffer.hpp"
#include "facet/render_job.hpp"
#include "facet/renderer.hpp"
#include "keys.hpp"
#include "viewer_state.hpp"

namespace facet::web {
namespace {

// Everything the page shows, kept between the calls page.js makes once per animation frame or per event.
struct Page {
  viewer::Showing showing = viewer::Showing::demo(Demo::cube);
  viewer::Toggles toggles;
  viewer::Orbit orbit;
  LookSpec look;         // the model's own look: facet's studio, or an environment the user opened
  Renderer renderer{1};  // one thread: the page runs from any static server (docs/WEB.md)
  std::optional<Framebuffer> target;
  double animation = 0.0;                 // seconds of the demo's animation shown, which stops while paused
  std::optional<double> last_time;        // the page's clock at the previous frame
  std::string text;                       // the last string handed to JavaScript
};

Page& page() {
  static Page p;
  return p;
}

// Runs `change` on the page; "" when it succeeds, else its one-line message (the page left as it was).
template <class Change>
const char* attempt(Change change) {
  Page& p = page();
  try {
    change(p);
    p.text.clear();
  } catch (const std::bad_alloc&) {
    p.text = "out of memory";
  } catch (const std::exception& e) {
    p.text = e.what();
  }
  return p.text.c_str();
}

// Replaces what is shown, keeping the toggles; a failure leaves the previous scene and returns its message.
template <class Make>
const char* show(Make make) {
  return attempt([&](Page& p) {
    p.showing = make();
    p.orbit = viewer::Orbit{};
    p.animation = 0.0;
  });
}

}  // namespace
}  // namespace facet::web

using facet::web::page;

// The functions page.js calls. Strings returned stay valid until the next call that returns one.
extern "C" {

// Shows a demo by its `facet view --demo` name; "" on success, else the error.
EMSCRIPTEN_KEEPALIVE const char* facet_page_show_demo(const char* name) {
  return facet::web::show([name] {
    const std::optional<facet::Demo> demo = facet::parse_demo(name);
    if (!demo) throw std::invalid_argument(std::string("no demo named '") + name + "'");
    return facet::viewer::Showing::demo(*demo);
  });
}

// Opens a model file written into the module's file system; "" on success, else its one-line error.
EMSCRIPTEN_KEEPALIVE const char* facet_page_open_model(const char* path) {
  return facet::web::show([path] { return facet::viewer::Showing::model(path); });
}

// Lights the model's own look by an equirectangular Radiance .hdr written into the module's file system (the
// page's --hdri); "" on success, else its one-line error, the previous environment kept.
EMSCRIPTEN_KEEPALIVE const char* facet_page_open_environment(const char* path) {
  return facet::web::attempt([path](facet::web::Page& p) {
    facet::LookSpec look = p.look;
    look.hdri = path;
    facet::environment_for(look);  // read and prefiltered now, so that a bad file is refused here
    p.look = look;
  });
}

// A key as typed ('w', '1', ' '): 1 if it is one of the viewer's keys, else 0.
EMSCRIPTEN_KEEPALIVE int facet_page_key(int key) {
  if (key <= 0 || key > 127) return 0;
  return facet::viewer::apply_key(static_cast<char>(key), page().toggles, page().orbit, &page().showing) !=
         facet::viewer::KeyAction::unknown;
}

// A mouse drag of (dx, dy) pixels: a turn, or a pan across a view `height` pixels high.
EMSCRIPTEN_KEEPALIVE void facet_page_drag(float dx, float dy, int pan, int height) {
  if (pan) facet::viewer::pan_by(page().orbit, {dx, dy}, height);
  else facet::viewer::turn_by(page().orbit, {dx, dy});
}

EMSCRIPTEN_KEEPALIVE void facet_page_zoom(float wheel_steps) { facet::viewer::zoom_by(page().orbit, wheel_steps); }

// Draws the frame for the page's clock (seconds) at width x height and returns its RGBA bytes, which stay valid
// until the next call; null if the frame cannot be drawn (its error is then in facet_page_error()).
EMSCRIPTEN_KEEPALIVE const std::uint32_t* facet_page_frame(int width, int height, double seconds) {
  facet::web::Page& p = page();
  if (p.last_time && !p.toggles.paused) p.animation += std::max(0.0, seconds - *p.last_time);
  p.animation = std::max(0.0, p.animation + p.toggles.steps / 30.0);  // the , and . keys: a frame back, forward
  p.toggles.steps = 0;
  p.last_time = seconds;
  try {
    facet::viewer::draw_frame(p.renderer, p.target, width, height, p.showing, p.animation, p.toggles, p.orbit,
                              p.look);
  } catch (const std::exception& e) {
    p.text = e.what();
    p.target.reset();
    return nullptr;
  }
  return p.target->color().data();
}

EMSCRIPTEN_KEEPALIVE const char* facet_page_error() { return page().text.c_str(); }

// What is shown and how, for the page's status line: "demo torus - Phong, wireframe, paused".
EMSCRIPTEN_KEEPALIVE const char* facet_page_status() {
  facet::web::Page& p = page();
  p.text = p.showing.title() + " - " + facet::viewer::describe(p.toggles);
  return p.text.c_str();
}

// The toggles as bits for the page's buttons: 1 wireframe, 2 edges, 4 culling (back or front), 8 depth test,
// 16 painter's, 32 shuffled, 64 orthographic, 128 anti-aliased, 256 paused, 512 help, 1024 a colour map; the
// shading key (0-7) << 12.
EMSCRIPTEN_KEEPALIVE int facet_page_toggles() {
  const facet::viewer::Toggles& t = page().toggles;
  const bool culling = t.cull && *t.cull != facet::CullMode::none;
  return t.wireframe | t.edges << 1 | culling << 2 | t.depth_test << 3 | t.painter << 4 | (t.shuffles != 0) << 5 |
         t.orthographic << 6 | t.antialias << 7 | t.paused << 8 | t.help << 9 |
         (t.color_map != facet::ColorMap::none) << 10 |
         (t.shading ? static_cast<int>(*t.shading) : 0) << 12;
}

}  // extern "C"

// The runtime stays up after main returns: page.js drives everything through the functions above.
int main() { return 0; }
