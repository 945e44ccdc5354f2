// render_job.cpp - a RenderJob performed: load, frame, view, look, draw, write every output or none.
#include "facet/render_job.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/file_util.hpp"
#include "facet/error.hpp"
#include "facet/image_io.hpp"
#include "facet/model_io.hpp"
#include "facet/output_template.hpp"
#include "facet/text.hpp"
#include "job/io/output_file.hpp"
#include "job/job_frame.hpp"

namespace facet {

using detail::JobFrame;
using detail::Stopwatch;

std::vector<std::filesystem::path> output_paths(const OutputSpec& o) {
  std::vector<std::filesystem::path> paths;
  for (const std::filesystem::path* p : {&o.color, &o.depth, &o.normal, &o.ids, &o.mask, &o.camera, &o.motion})
    if (!p->empty()) paths.push_back(*p);
  return paths;
}

void check_output_formats(const OutputSpec& o, bool animation) {
  struct Rule {
    const std::filesystem::path* path;
    const char* what;
    std::vector<std::string_view> extensions;
  };
  // An animation is one GIF or video, or PNG frames when its name numbers them ({frame}).
  const bool sequence = animation && template_has(o.color.string(), "frame");
  const Rule rules[] = {animation && !sequence
                            ? Rule{&o.color,
                                   "an animation as .gif, .mp4 or .webm, or as PNG frames named with {frame}",
                                   {".gif", ".mp4", ".webm"}}
                            : Rule{&o.color, "the colour image as PNG (.png)", {".png"}},
                        {&o.depth, "depth as .npy or .exr", {".npy", ".exr"}},
                        {&o.normal, "normals as .npy or .exr", {".npy", ".exr"}},
                        {&o.ids, "ids as .npy", {".npy"}},
                        {&o.mask, "the mask as PNG (.png)", {".png"}},
                        {&o.camera, "the camera as JSON (.json)", {".json"}},
                        {&o.motion, "motion as .npy or .exr", {".npy", ".exr"}}};
  for (const Rule& rule : rules) {
    const std::string extension = lower_extension(*rule.path);
    if (extension.empty()) continue;
    if (std::find(rule.extensions.begin(), rule.extensions.end(), extension) == rule.extensions.end())
      throw std::invalid_argument(rule.path->string() + ": facet writes " + rule.what + ", not " + extension);
  }
}

std::size_t remove_stale_temporaries(std::span<const OutputSpec> outputs) {
  std::vector<std::filesystem::path> paths;
  for (const OutputSpec& spec : outputs)
    for (std::filesystem::path& path : output_paths(spec)) paths.push_back(std::move(path));
  return remove_stale_temporaries(std::span<const std::filesystem::path>(paths));
}

std::optional<OutputClash> find_output_clash(std::span<const OutputSpec> outputs) {
  std::map<std::filesystem::path, std::size_t> writer;  // each path and the first entry that writes it
  for (std::size_t k = 0; k < outputs.size(); ++k)
    for (const std::filesystem::path& path : output_paths(outputs[k])) {
      const auto [it, added] = writer.try_emplace(path.lexically_normal(), k);
      if (!added && it->second != k) return OutputClash{it->second, k, path};
    }
  return std::nullopt;
}

FrameBuffers draw_buffers(Renderer& renderer, Framebuffer& target, Scene& scene, const View& view,
                          const SceneOptions& options, glm::vec4 clear, const BufferRequest& request,
                          Framebuffer* centres, const LaterFrame* later) {
  const bool surface_pass = request.normal || request.ids || request.motion;
  if (surface_pass && (options.wireframe || options.edges))
    throw std::invalid_argument("normal, id and motion outputs show surfaces: not with wireframe or edges");
  if (request.motion && !(later && later->scene))
    throw std::invalid_argument("motion: needs the next frame (a model's animation, or a later camera)");
  // The colour pass's depth is read only for a 1-sample depth or mask; otherwise it stays in tile memory.
  target.keep_depth((request.depth || request.mask) && target.samples() == 1);
  renderer.clear(target, clear, 1.0f);
  scene.render(renderer, target, view, options);
  renderer.finish(target);
  FrameBuffers out;
  out.width = target.width();
  out.height = target.height();
  if (request.color) out.color = target.rgba8();
  // Depth, mask, ids and normals describe the surface at each pixel's centre, whatever the sample count, as the
  // colour pass does with one sample: with several, depth and mask come from a pass of the same scene at one sample,
  // unlit (its depth is the colour pass's at the centres), and ids from the id pass at one sample. The depth and the
  // mask come from one depth read, so every buffer agrees on which pixels are empty.
  std::optional<Framebuffer> made;
  const auto centre_target = [&]() -> Framebuffer& {
    if (centres && centres->width() == target.width() && centres->height() == target.height() &&
        centres->samples() == 1)
      return *centres;
    if (!made) made.emplace(target.width(), target.height());
    return *made;
  };
  if (request.depth || request.mask) {
    if (target.samples() == 1) {
      out.depth = linear_depth(renderer, target, view.clip_from_view);
    } else {
      Framebuffer& plain_target = centre_target();
      plain_target.keep_depth(true);
      SceneOptions plain = options;
      plain.shading = Shading::unlit;
      plain.environment_background = plain.shadows = plain.ambient_occlusion = false;
      renderer.clear(plain_target, clear, 1.0f);
      scene.render(renderer, plain_target, view, plain);
      out.depth = linear_depth(renderer, plain_target, view.clip_from_view);
    }
  }
  if (request.mask) {
    out.mask.resize(out.depth.size());
    for (std::size_t i = 0; i < out.depth.size(); ++i) out.mask[i] = out.depth[i] > 0.0f ? 255 : 0;
    if (!request.depth) out.depth = {};
  }
  if (surface_pass) {
    // Ids and the normals found from them come from pixel centres, as depth and the mask do: never a blend.
    out.surfaces = scene.render_ids(renderer, centre_target(), view, options);
    if (request.normal) out.normal = scene.camera_normals(out.surfaces, view);
    if (request.ids) out.ids = file_ids(scene, out.surfaces);
    if (request.motion) out.motion = screen_motion(scene, out.surfaces, view, *later->scene, later->view);
  }
  return out;
}

std::vector<std::uint32_t> file_ids(const Scene& scene, const SurfaceIds& surfaces,
                                    std::span<const std::uint32_t> instance_ids) {
  std::vector<std::uint32_t> out(2 * surfaces.instance.size(), kNoSurface);
  for (std::size_t p = 0; p < surfaces.instance.size(); ++p) {
    const std::uint32_t instance = surfaces.instance[p];
    if (instance == kNoSurface) continue;
    const Mesh& mesh = *scene.instances()[instance].mesh;
    out[2 * p] = instance_ids.empty() ? mesh.instance_id(surfaces.triangle[p]) : instance_ids[instance];
    out[2 * p + 1] = mesh.face_id(surfaces.triangle[p]);
  }
  return out;
}

void draw_and_write(Renderer& renderer, Framebuffer& target, Scene& scene, const View& view,
                    const SceneOptions& options, glm::vec4 clear, const OutputSpec& outputs, RenderTimings* timings,
                    const LaterFrame* later) {
  Stopwatch clock;
  // The colour image is encoded straight from the framebuffer, not from a copy.
  const BufferRequest request{.color = false,
                              .depth = !outputs.depth.empty(),
                              .normal = !outputs.normal.empty(),
                              .ids = !outputs.ids.empty(),
                              .mask = !outputs.mask.empty(),
                              .motion = !outputs.motion.empty()};
  const FrameBuffers buffers = draw_buffers(renderer, target, scene, view, options, clear, request, nullptr, later);
  if (timings) timings->draw = clock.lap();
  std::vector<std::filesystem::path> written;
  try {
    const int w = buffers.width, h = buffers.height;
    if (!outputs.color.empty()) {
      write_png(outputs.color, target, clear.a < 1.0f, renderer.threads());
      written.push_back(outputs.color);
    }
    if (!outputs.depth.empty()) {
      write_float_image(outputs.depth, w, h, 1, buffers.depth);
      written.push_back(outputs.depth);
    }
    if (!outputs.normal.empty()) {
      write_float_image(outputs.normal, w, h, 3, std::span(&buffers.normal.data()->x, 3 * buffers.normal.size()));
      written.push_back(outputs.normal);
    }
    if (!outputs.ids.empty()) {
      write_npy(outputs.ids, w, h, 2, buffers.ids);
      written.push_back(outputs.ids);
    }
    if (!outputs.mask.empty()) {
      write_png_gray(outputs.mask, w, h, buffers.mask);
      written.push_back(outputs.mask);
    }
    if (!outputs.motion.empty()) {
      write_float_image(outputs.motion, w, h, 2, std::span(&buffers.motion.data()->x, 2 * buffers.motion.size()));
      written.push_back(outputs.motion);
    }
    if (!outputs.camera.empty()) write_text(outputs.camera, camera_json(view, w, h));
    if (timings) timings->write = clock.lap();
  } catch (...) {
    for (const std::filesystem::path& path : written) discard_output(path);
    throw;
  }
}

// A contact sheet or turntable is a colour output alone, seen through cameras of its own.
void detail::check_colour_only(const RenderJob& job, const char* what, const char* flag) {
  const OutputSpec& o = job.outputs;
  if (!o.depth.empty() || !o.normal.empty() || !o.ids.empty() || !o.mask.empty() || !o.camera.empty() ||
      !o.motion.empty())
    throw std::invalid_argument(std::string(flag) + ": " + what +
                                " is a colour output alone; it has no depth, normal, ids, mask, motion or camera "
                                "output");
  if (job.camera.file_camera)
    throw std::invalid_argument(std::string(flag) + ": " + what + " places its own cameras, not the file's");
  if (o.color.empty()) throw std::invalid_argument(std::string(flag) + ": " + what + " needs a colour output to write");
}

namespace {

// The contact sheet: each view drawn into a cell framebuffer, copied into its place in the grid and labelled.
void render_sheet(const RenderJob& job, Renderer& renderer, RenderTimings* timings) {
  const OutputSpec& o = job.outputs;
  detail::check_colour_only(job, "a contact sheet", "views");
  const int n = static_cast<int>(job.views.size());
  const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  const int rows = (n + columns - 1) / columns;
  if (static_cast<long>(job.width) * columns > kMaxDimension || static_cast<long>(job.height) * rows > kMaxDimension)
    throw std::invalid_argument("views: a sheet of " + std::to_string(columns) + "x" + std::to_string(rows) +
                                " views of " + std::to_string(job.width) + "x" + std::to_string(job.height) +
                                " is over " + std::to_string(kMaxDimension) + " pixels a side");
  // The model is prepared once, as for any render; each view reuses it.
  JobFrame frame = detail::prepare_job(job, timings);
  Stopwatch clock;
  const Framing framing = framing_of(*frame.scene.instances()[0].mesh, job.model.string());
  const float aspect = static_cast<float>(job.width) / static_cast<float>(job.height);
  const int sheet_width = job.width * columns, sheet_height = job.height * rows;
  std::vector<std::uint8_t> sheet(static_cast<std::size_t>(sheet_width) * sheet_height * 4);
  for (std::size_t p = 0; p < sheet.size(); p += 4)  // empty cells show the background
    for (int c = 0; c < 4; ++c)
      sheet[p + static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(std::lround(frame.clear[c] * 255.0f));
  Framebuffer cell(job.width, job.height, job.samples);
  cell.keep_depth(false);
  const int scale = job.width >= 480 ? 2 : 1;
  for (int k = 0; k < n; ++k) {
    const SheetView view = job.views[static_cast<std::size_t>(k)];
    const View v = make_view(sheet_camera(view, job.camera, framing, aspect), framing, aspect);
    const SceneOptions options = detail::options_for_view(job, frame, v);
    renderer.clear(cell, frame.clear, 1.0f);
    frame.scene.render(renderer, cell, v, options);
    renderer.finish(cell);
    // The label goes on the cell before it joins the sheet, so a label wider than its cell is cut at the cell's edge.
    std::vector<std::uint8_t> rgba = cell.rgba8();
    const std::string label = sheet_view_label(view);
    const TextSize size = text_size(label, scale);
    fill_rect(rgba, job.width, job.height, 0, 0, size.width + 8 * scale, size.height + 6 * scale,
              glm::vec4(0.0f, 0.0f, 0.0f, 0.55f));
    draw_text(rgba, job.width, job.height, 4 * scale, 4 * scale, label, glm::vec4(1.0f), scale);
    const int x0 = (k % columns) * job.width, y0 = (k / columns) * job.height;
    for (int y = 0; y < job.height; ++y)
      std::copy_n(rgba.begin() + static_cast<std::ptrdiff_t>(y) * job.width * 4, job.width * 4,
                  sheet.begin() + (static_cast<std::ptrdiff_t>(y0 + y) * sheet_width + x0) * 4);
  }
  if (timings) timings->draw = clock.lap();
  write_png(o.color, sheet_width, sheet_height, sheet, frame.clear.a < 1.0f, renderer.threads());
  if (timings) timings->write = clock.lap();
}

}  // namespace

void render(const RenderJob& job, Renderer& renderer, RenderTimings* timings) {
  const std::vector<std::filesystem::path> paths = output_paths(job.outputs);
  for (std::size_t i = 0; i < paths.size(); ++i)
    for (std::size_t k = i + 1; k < paths.size(); ++k)
      if (paths[i].lexically_normal() == paths[k].lexically_normal())
        throw std::invalid_argument("outputs: " + paths[k].string() + " is named twice");
  const bool animated =
      job.turntable > 0 || job.animation.play || (job.demo && (job.frames > 1 || is_animation_path(job.outputs.color)));
  check_output_formats(job.outputs, animated);
  if (job.demo) return detail::render_demo(job, renderer, timings);
  if (!job.views.empty() && job.turntable > 0)
    throw std::invalid_argument("views: a contact sheet is one image, not a turntable");
  if (job.animation.play) return detail::render_model_animation(job, renderer, timings);
  if (!job.views.empty()) return render_sheet(job, renderer, timings);
  if (job.turntable > 0) return detail::render_turntable(job, renderer, timings);
  JobFrame frame = detail::prepare_job(job, timings);
  Framebuffer target(job.width, job.height, job.samples);
  const LaterFrame later = frame.later();
  draw_and_write(renderer, target, frame.scene, frame.view, frame.options, frame.clear, job.outputs, timings, &later);
}

FrameBuffers render_buffers(const RenderJob& job, Renderer& renderer, const BufferRequest& request,
                            std::string* camera) {
  JobFrame frame = detail::prepare_job(job, nullptr, request.motion);
  Framebuffer target(job.width, job.height, job.samples);
  const LaterFrame later = frame.later();
  FrameBuffers buffers =
      draw_buffers(renderer, target, frame.scene, frame.view, frame.options, frame.clear, request, nullptr, &later);
  if (camera) *camera = camera_json(frame.view, job.width, job.height);
  return buffers;
}

}  // namespace facet
