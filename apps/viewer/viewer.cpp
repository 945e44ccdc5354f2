// viewer.cpp - the viewer's window: SDL2 events in, facet's frames out; SDL only presents the pixels facet drew.
#include "viewer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "facet/error.hpp"
#include "facet/framebuffer.hpp"
#include "facet/image_io.hpp"
#include "facet/renderer.hpp"
#include "facet/text.hpp"
#include "keys.hpp"
#include "sdl.hpp"
#include "viewer_state.hpp"

namespace facet::viewer {

namespace {

using Clock = std::chrono::steady_clock;

// SDL's video subsystem and the window, released in the right order whatever ends the run.
class Window {
 public:
  Window(const std::string& title, int width, int height) {
    // The window surface is written by facet and copied to the screen (XShm on X11). Without this hint SDL backs
    // it with an OpenGL texture, which on a machine without a GPU means Mesa's software rasterizer redrawing each
    // frame: a fifth of the CPU time at 1280x720.
    sdl().SDL_SetHint(SDL_HINT_FRAMEBUFFER_ACCELERATION, "0");
    if (sdl().SDL_Init(SDL_INIT_VIDEO) != 0)
      throw std::runtime_error(std::string("cannot open a window: ") + sdl().SDL_GetError());
    window_ = sdl().SDL_CreateWindow(title.c_str(), SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED, width, height,
                                     SDL_WINDOW_RESIZABLE);
    if (!window_) {
      const std::string error = sdl().SDL_GetError();
      sdl().SDL_Quit();
      throw std::runtime_error("cannot open a window: " + error);
    }
    sdl().SDL_EventState(SDL_DROPFILE, SDL_ENABLE);
  }
  ~Window() {
    sdl().SDL_DestroyWindow(window_);
    sdl().SDL_Quit();
  }
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  SDL_Window* get() const { return window_; }

  // Copies an image of the surface's size into the window: RGBA bytes, or facet's packed pixels (red in the low
  // byte: SDL's ABGR8888 whatever the machine's byte order). The surface is asked for anew each time: a resize
  // replaces it.
  void present(const void* pixels, bool packed, int width, int height) {
    SDL_Surface* surface = sdl().SDL_GetWindowSurface(window_);
    if (!surface || surface->w != width || surface->h != height) return;  // resized meanwhile: the next frame fits
    if (SDL_MUSTLOCK(surface)) sdl().SDL_LockSurface(surface);
    sdl().SDL_ConvertPixels(width, height, packed ? SDL_PIXELFORMAT_ABGR8888 : SDL_PIXELFORMAT_RGBA32, pixels,
                            width * 4, surface->format->format, surface->pixels, surface->pitch);
    if (SDL_MUSTLOCK(surface)) sdl().SDL_UnlockSurface(surface);
    sdl().SDL_UpdateWindowSurface(window_);
  }

  // The size frames are drawn at: the window surface's, in pixels.
  void size(int& width, int& height) const {
    SDL_Surface* surface = sdl().SDL_GetWindowSurface(window_);
    if (surface) {
      width = surface->w;
      height = surface->h;
    } else {
      sdl().SDL_GetWindowSize(window_, &width, &height);
    }
  }

 private:
  SDL_Window* window_ = nullptr;
};

// The framebuffer's colour as RGBA bytes in `out`.
void compose(const Framebuffer& fb, std::vector<std::uint8_t>& out) {
  const std::span<const std::uint32_t> color = fb.color();
  out.resize(color.size() * 4);
  for (std::size_t i = 0; i < color.size(); ++i)
    for (std::size_t c = 0; c < 4; ++c) out[i * 4 + c] = static_cast<std::uint8_t>(color[i] >> (8 * c));
}

// A block of text on a dark box at the top left.
void overlay(std::vector<std::uint8_t>& rgba, int width, int height, const std::string& text, glm::vec4 color) {
  const int scale = width >= 900 ? 2 : 1;
  const TextSize size = text_size(text, scale);
  fill_rect(rgba, width, height, 8, 8, size.width + 16, size.height + 12, glm::vec4(0.0f, 0.0f, 0.0f, 0.7f));
  draw_text(rgba, width, height, 16, 14, text, color, scale);
}

// The key an SDL key event means to the viewer, as a character; 0 for keys it has no use for.
char key_of(const SDL_KeyboardEvent& key) {
  const SDL_Keycode k = key.keysym.sym;
  if (k == SDLK_ESCAPE) return '\x1b';
  if (k == SDLK_SPACE) return ' ';
  if (k == SDLK_COMMA || k == SDLK_PERIOD) return static_cast<char>(k);
  if ((k >= SDLK_a && k <= SDLK_z) || (k >= SDLK_0 && k <= SDLK_9)) return static_cast<char>(k);
  return 0;
}

}  // namespace

int run_viewer(const ViewerOptions& options) {
  Showing showing = options.demo ? Showing::demo(*options.demo) : Showing::model(options.model, options.load);
  Toggles toggles;
  Orbit orbit;
  for (const char key : options.keys)
    if (apply_key(key, toggles, orbit, &showing) == KeyAction::unknown)
      throw std::invalid_argument(std::string("--keys: '") + key + "' is not a viewer key (facet view --help)");

  Window window("facet view - " + showing.title(), options.width, options.height);
  Renderer renderer(options.threads);
  std::optional<Framebuffer> target;
  std::vector<std::uint8_t> shown;  // the frame as shown, when it is not the framebuffer itself
  bool composed = false;
  int width = options.width, height = options.height;
  std::string error;  // the last model that failed to load, shown until the next one loads
  double animation = 0.0, fps = 0.0;
  int frames = 0, frames_since_title = 0;
  const Clock::time_point start = Clock::now();
  Clock::time_point last = start, title_time = start;
  bool running = true, dirty = true;

  while (running) {
    SDL_Event event;
    const bool animating = showing.animated() && !toggles.paused;
    // Nothing moves and nothing was asked: sleep until something happens rather than redraw the same frame.
    bool have_event = (!animating && !dirty && options.frames == 0) ? sdl().SDL_WaitEventTimeout(&event, 500) != 0
                                                                    : sdl().SDL_PollEvent(&event) != 0;
    for (; have_event; have_event = sdl().SDL_PollEvent(&event) != 0) {
      dirty = true;
      switch (event.type) {
        case SDL_QUIT: running = false; break;
        case SDL_KEYDOWN:
          if (const char key = key_of(event.key); key && apply_key(key, toggles, orbit, &showing) == KeyAction::quit)
            running = false;
          break;
        case SDL_MOUSEMOTION: {
          const bool shift = (sdl().SDL_GetModState() & KMOD_SHIFT) != 0;
          const Uint32 buttons = event.motion.state;
          const glm::vec2 drag(static_cast<float>(event.motion.xrel), static_cast<float>(event.motion.yrel));
          if ((buttons & SDL_BUTTON_RMASK) || ((buttons & SDL_BUTTON_LMASK) && shift)) pan_by(orbit, drag, height);
          else if (buttons & SDL_BUTTON_LMASK) turn_by(orbit, drag);
          break;
        }
        case SDL_MOUSEWHEEL: zoom_by(orbit, static_cast<float>(event.wheel.y)); break;
        case SDL_DROPFILE: {
          const std::string path = event.drop.file;
          sdl().SDL_free(event.drop.file);
          try {
            showing = Showing::model(path, options.load);
            orbit = Orbit{};
            error.clear();
            sdl().SDL_SetWindowTitle(window.get(), ("facet view - " + showing.title()).c_str());
          } catch (const std::exception& e) {
            error = e.what();
          }
          break;
        }
        default: break;
      }
    }
    if (!running) break;

    const Clock::time_point now = Clock::now();
    if (!toggles.paused)
      animation = options.frames ? frames / 60.0 : animation + std::chrono::duration<double>(now - last).count();
    animation = std::max(0.0, animation + toggles.steps / 30.0);
    toggles.steps = 0;
    last = now;
    window.size(width, height);
    draw_frame(renderer, target, width, height, showing, animation, toggles, orbit, options.look);
    // The framebuffer goes to the window as it is, unless it is written over.
    composed = toggles.help || !error.empty();
    if (composed) {
      compose(*target, shown);
      if (toggles.help) overlay(shown, width, height, kHelpText, glm::vec4(1.0f));
      if (!error.empty()) overlay(shown, width, height, "cannot open: " + error, glm::vec4(1.0f, 0.5f, 0.4f, 1.0f));
      window.present(shown.data(), false, width, height);
    } else {
      window.present(target->color().data(), true, width, height);
    }
    ++frames;
    ++frames_since_title;
    dirty = false;

    const double since_title = std::chrono::duration<double>(now - title_time).count();
    if (since_title >= 0.5) {
      fps = frames_since_title / since_title;
      frames_since_title = 0;
      title_time = now;
      char rate[32];
      std::snprintf(rate, sizeof rate, "%.1f fps", fps);
      const std::string title = "facet view - " + showing.title() + " - " + describe(toggles) + " - " + rate;
      sdl().SDL_SetWindowTitle(window.get(), title.c_str());
    }
    if (options.frames && frames >= options.frames) running = false;
  }

  if (!options.screenshot.empty() && target) {
    if (composed) write_png(options.screenshot, width, height, shown, false);
    else write_png(options.screenshot, *target, false);
  }
  if (options.frames) {
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::fprintf(stderr, "facet: view: %d frames in %.3f s (%.1f fps)\n", frames, seconds, frames / seconds);
  }
  return 0;
}

}  // namespace facet::viewer
