// viewer.hpp - `facet view`: a window in which a person orbits a model or a demo and flips the pipeline's switches.
#pragma once

#include <optional>
#include <string>

#include "facet/demo_scenes.hpp"
#include "facet/model_io.hpp"
#include "facet/render_job.hpp"

namespace facet::viewer {

struct ViewerOptions {
  std::string model;         // a model file, or empty with a demo
  std::optional<Demo> demo;  // a built-in demo instead of a model
  int width = 1280, height = 720;
  int threads = 0;         // 0: one per hardware thread
  int frames = 0;          // quit after this many frames; 0: run until closed
  std::string keys;        // pressed in order before the first frame
  std::string screenshot;  // the last frame shown is written here as PNG
  LoadOptions load;        // what model files (the first and those dropped on the window) may make facet read
  // The model's own look's light: environment, key light, tone mapping, model lights, shadows, ambient occlusion;
  // the keys switch the shading and the rest.
  LookSpec look;
};

// Opens the window (SDL2; under X11, Wayland, or Xvfb for tests) and runs until it is closed, q or Esc, or
// `frames` frames. With `frames`, the animation advances 1/60 s per frame rather than with the clock, so scripted
// runs show the same pictures every time, and a line "facet: view: N frames in S s (F fps)" goes to stderr.
// Throws InputError for a first model that cannot be loaded and std::runtime_error when no window can be opened;
// a model dropped on the window later that cannot be loaded is shown as an error over the previous one.
int run_viewer(const ViewerOptions& options);

}  // namespace facet::viewer
