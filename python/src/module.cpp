// module.cpp - facet._facet, the compiled core of the Python package: renderers that return frames as numpy arrays.
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "arrays.hpp"
#include "facet/error.hpp"
#include "facet/framebuffer.hpp"
#include "facet/model_io.hpp"
#include "facet/names.hpp"
#include "facet/render_job.hpp"
#include "facet/renderer.hpp"
#include "facet/view_spec.hpp"
#include "meshes.hpp"

namespace facet::python {

namespace {

Shading shading_named(const std::string& name) {
  if (const std::optional<Shading> shading = parse_shading(name)) return *shading;
  value_error("shading: unknown shading '" + name + "' (" + listed(shading_names()) + ")");
}

// The buffers a list of names asks for; raises ValueError for an unknown name.
BufferRequest request_of(const std::vector<std::string>& names) {
  BufferRequest r{.color = false};
  for (const std::string& n : names) {
    const std::optional<bool BufferRequest::*> field = parse_name(buffer_names(), n);
    if (!field) value_error("buffers: unknown buffer '" + n + "' (" + listed(buffer_names()) + ")");
    r.** field = true;
  }
  return r;
}

// A light as renderer.py describes it: (kind, vector, colour, intensity, spot direction, range or None, inner cone,
// outer cone, casts shadows), the vector being the direction towards a directional light or a point or spot light's
// position. The Python classes check the values; this guards the module against hand-made tuples.
Light light_of(py::handle description) {
  const auto t = description.cast<py::tuple>();
  if (t.size() != 9)
    value_error("light: expected (kind, vector, color, intensity, direction, range, inner, outer, shadows)");
  const auto vec3 = [&](std::size_t i, const char* name) {
    return finite_rows<3>(py::array::ensure(t[i]).reshape({1, 3}), name)[0];
  };
  Light out;
  const std::string kind = t[0].cast<std::string>();
  if (kind == "directional") out.kind = Light::Kind::directional;
  else if (kind == "point") out.kind = Light::Kind::point;
  else if (kind == "spot") out.kind = Light::Kind::spot;
  else value_error("light: unknown kind '" + kind + "'");
  out.vector = vec3(1, "light");
  out.color = vec3(2, "light colour");
  out.intensity = t[3].cast<float>();
  if (!(out.intensity >= 0.0f) || !std::isfinite(out.intensity))
    value_error("light: intensity must be finite and not negative");
  out.spot_direction = vec3(4, "light direction");
  // A pose whose axis is zero gives no direction; normalizing it would light every pixel with NaN.
  if (out.kind == Light::Kind::directional && glm::dot(out.vector, out.vector) == 0.0f)
    value_error("light: a directional light's pose has a zero z axis");
  if (out.kind == Light::Kind::spot && glm::dot(out.spot_direction, out.spot_direction) == 0.0f)
    value_error("light: a spot light's pose has a zero z axis");
  out.range = t[5].is_none() ? 0.0f : t[5].cast<float>();
  if (!(out.range >= 0.0f)) value_error("light: range must not be negative");
  if (std::isinf(out.range)) out.range = 0.0f;  // unlimited, as None
  out.inner_cone = t[6].cast<float>();
  out.outer_cone = t[7].cast<float>();
  if (!(out.inner_cone >= 0.0f && out.inner_cone < out.outer_cone && out.outer_cone <= 1.5707964f))
    value_error("light: cone angles need 0 <= inner < outer <= pi/2");
  out.casts_shadows = t[8].cast<bool>();
  return out;
}

// The colour of packed RGBA pixels as bytes, with alpha or without: what the colour array holds.
std::vector<std::uint8_t> color_bytes(std::span<const std::uint32_t> pixels, bool rgba) {
  const std::size_t channels = rgba ? 4 : 3;
  std::vector<std::uint8_t> out(pixels.size() * channels);
  for (std::size_t i = 0; i < pixels.size(); ++i)
    for (std::size_t c = 0; c < channels; ++c) out[channels * i + c] = static_cast<std::uint8_t>(pixels[i] >> (8 * c));
  return out;
}

// The frame's buffers as numpy arrays, keyed by name; vectors are handed over, not copied. b.color holds RGBA bytes,
// or, when its size says so, the RGB bytes already.
py::dict arrays_of(FrameBuffers&& b, const BufferRequest& request, bool rgba, std::vector<std::uint32_t>&& ids) {
  const py::ssize_t h = b.height, w = b.width;
  py::dict out;
  if (request.color) {
    const auto pixels = static_cast<std::size_t>(w * h);
    if (!rgba && b.color.size() == 4 * pixels) {
      std::vector<std::uint8_t> rgb(3 * pixels);
      for (std::size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c) rgb[3 * i + c] = b.color[4 * i + c];
      b.color = std::move(rgb);
    }
    out["color"] = to_numpy(std::move(b.color), {h, w, rgba ? 4 : 3});
  }
  if (request.depth) out["depth"] = to_numpy(std::move(b.depth), {h, w});
  if (request.normal) {
    std::vector<float> n(3 * b.normal.size());
    for (std::size_t i = 0; i < b.normal.size(); ++i)
      for (int c = 0; c < 3; ++c) n[3 * i + c] = b.normal[i][c];
    out["normal"] = to_numpy(std::move(n), {h, w, 3});
  }
  if (request.ids) out["ids"] = to_numpy(std::move(ids), {h, w, 2});
  if (request.mask) out["mask"] = to_numpy(std::move(b.mask), {h, w});
  if (request.motion) {
    std::vector<float> m(2 * b.motion.size());
    for (std::size_t i = 0; i < b.motion.size(); ++i) m[2 * i] = b.motion[i].x, m[2 * i + 1] = b.motion[i].y;
    out["motion"] = to_numpy(std::move(m), {h, w, 2});
  }
  return out;
}

// One renderer per Python OffscreenRenderer: its threads and framebuffer, used by one render at a time.
class RendererCore {
 public:
  RendererCore(int width, int height, int threads, int samples)
      : renderer_(threads), target_(width, height, samples), centres_(width, height) {}

  int width() const { return target_.width(); }
  int height() const { return target_.height(); }

  // Draws scene through the view and returns the buffers named, with the GIL released while drawing.
  py::dict render(SceneCore& scene, py::handle view_from_world, py::handle clip_from_view, float near, float far,
                  const std::string& shading, bool cull_back, bool wireframe, py::list lights, py::handle ambient,
                  py::handle background, bool rgba, float point_size, const std::vector<std::string>& buffers) {
    const View view = view_of(view_from_world, clip_from_view, near, far);
    // pyrender's lighting in the job layer's terms: the scene's lights and ambient colour, no environment.
    LookSpec look;
    look.shading = shading_named(shading);
    look.wireframe = wireframe;
    // Back faces are culled per material, as pyrender culls them (the look's default: single-sided materials only,
    // and every mesh the module makes names its materials' sides, materials.hpp); SKIP_CULL_FACES draws them all.
    if (!cull_back) look.cull = CullMode::none;
    for (const py::handle light : lights) look.lights.push_back(light_of(light));
    // Shadows are drawn for the lights the flags ask them of (each tuple says whether its light casts).
    look.shadows = std::any_of(look.lights.begin(), look.lights.end(),
                               [](const Light& l) { return l.casts_shadows && l.kind != Light::Kind::point; });
    look.ambient = finite_rows<3>(py::array::ensure(ambient).reshape({1, 3}), "ambient_light")[0];
    const glm::vec4 clear = finite_rows<4>(py::array::ensure(background).reshape({1, 4}), "bg_color")[0];
    look.model_lights = false;
    look.tone_mapping = ToneMapping::none;  // pyrender's shader clamps; it maps no tones
    look.point_size = point_size;
    const SceneOptions options = scene_options(look, view.view_from_world, Shading::automatic, glm::vec3(clear));
    const BufferRequest request = request_of(buffers);
    FrameBuffers frame;
    std::vector<std::uint32_t> ids;
    {
      py::gil_scoped_release released;
      std::scoped_lock own(mutex_);
      std::shared_lock shared(scene.mutex);
      BufferRequest drawn = request;
      drawn.color = false;  // read below straight from the framebuffer, in the array's own layout
      frame = draw_buffers(renderer_, target_, scene.scene, view, options, clear, drawn, &centres_);
      if (request.color) frame.color = color_bytes(target_.color(), rgba);
      // Python numbers instances by their nodes, not by the file's ids that draw_buffers gives.
      if (request.ids) ids = file_ids(scene.scene, frame.surfaces, scene.node_ids);
    }
    return arrays_of(std::move(frame), request, rgba, std::move(ids));
  }

  std::string camera(py::handle view_from_world, py::handle clip_from_view, float near, float far) const {
    return camera_json(view_of(view_from_world, clip_from_view, near, far), width(), height());
  }

 private:
  static View view_of(py::handle view_from_world, py::handle clip_from_view, float near, float far) {
    return View{matrix4(view_from_world, "view"), matrix4(clip_from_view, "projection"), near, far};
  }

  Renderer renderer_;
  Framebuffer target_;
  Framebuffer centres_;  // draw_buffers' one-sample passes (depth, ids) of a multisampled target, kept between frames
  std::mutex mutex_;
};

// facet.render()'s work: a RenderJob, as `facet render` builds it, drawn into buffers.
py::dict render_file(const std::string& model, int width, int height, int threads, int samples,
                     const std::string& shading, float azimuth, float elevation, const std::string& projection,
                     const std::string& up, std::optional<int> camera_index, py::handle background,
                     const std::vector<std::string>& buffers, bool rgba, bool allow_external_files,
                     py::handle max_triangles, py::handle max_points, py::handle max_texture_size,
                     std::optional<float> eye_dome_lighting, const std::string& color_map,
                     std::optional<std::string> animation, std::optional<double> time, double fps,
                     std::optional<double> motion_time, float motion_azimuth, float motion_elevation) {
  if (width < 1 || height < 1 || width > kMaxDimension || height > kMaxDimension)
    value_error("width and height must lie in 1.." + std::to_string(kMaxDimension));
  if (samples != 1 && samples != 2 && samples != 4 && samples != 8)
    value_error("samples: expected 1, 2, 4 or 8, got " + std::to_string(samples));
  RenderJob job;
  job.model = model;
  job.load = load_options_of(allow_external_files, max_triangles, max_points, max_texture_size);
  job.width = width;
  job.height = height;
  job.samples = samples;
  job.camera.azimuth_degrees = azimuth;
  job.camera.elevation_degrees = elevation;
  job.camera.file_camera = camera_index;
  const std::optional<Projection> kind = parse_projection(projection);
  if (!kind) value_error("projection: unknown projection '" + projection + "' (" + listed(projection_names()) + ")");
  job.camera.projection = *kind;
  const std::optional<UpAxis> axis = parse_up_axis(up);
  if (!axis) value_error("up: expected +X, -X, +Y, -Y, +Z or -Z, got '" + up + "'");
  job.camera.up = *axis;
  if (shading != "automatic") job.look.shading = shading_named(shading);
  job.look.eye_dome_lighting = eye_dome_lighting;
  const std::optional<ColorMap> map = parse_name(color_map_names(), color_map);
  if (!map) value_error("color_map: unknown colour map '" + color_map + "' (" + listed(color_map_names()) + ")");
  job.look.color_map = *map;
  if (!background.is_none()) {
    const glm::vec4 bg = finite_rows<4>(py::array::ensure(background).reshape({1, 4}), "background")[0];
    job.look.background = glm::vec3(bg);
    job.look.transparent_background = bg.a < 1.0f;
  }
  if (animation) job.animation.name = *animation;
  if (time && !std::isfinite(*time)) value_error("time: must be a finite number of seconds");
  job.animation.time = time;
  if (!(fps >= 1.0 && fps <= kMaxAnimationFps))
    value_error("fps: must lie in 1.." + std::to_string(static_cast<int>(kMaxAnimationFps)));
  job.animation.fps = fps;
  if (motion_time && !std::isfinite(*motion_time)) value_error("motion_time: must be a finite number of seconds");
  if (!std::isfinite(motion_azimuth) || !std::isfinite(motion_elevation))
    value_error("motion_azimuth, motion_elevation: must be finite numbers of degrees");
  job.motion = {motion_time, motion_azimuth, motion_elevation};
  const BufferRequest request = request_of(buffers);
  FrameBuffers frame;
  std::string camera;
  {
    py::gil_scoped_release released;
    Renderer renderer(threads);
    frame = render_buffers(job, renderer, request, &camera);
  }
  std::vector<std::uint32_t> ids = std::move(frame.ids);
  py::dict out = arrays_of(std::move(frame), request, rgba, std::move(ids));
  out["camera"] = py::module_::import("json").attr("loads")(camera);
  return out;
}

}  // namespace

}  // namespace facet::python

PYBIND11_MODULE(_facet, m) {
  namespace py = pybind11;
  using namespace facet::python;
  m.doc() = "facet's compiled core: meshes, scenes and renderers; use the facet package, not this module.";
  // The library's messages name a setting by the keyword argument that sets it (facet.render, Mesh.from_file).
  facet::spell_settings([](std::string_view name) { return "keyword " + std::string(name); });

  static py::exception<facet::InputError> load_error(
      m, "LoadError", py::make_tuple(py::handle(PyExc_OSError), py::handle(PyExc_ValueError)));
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const facet::InputError& e) {
      const bool missing = e.problem() == "no such file";
      PyErr_SetString(missing ? PyExc_FileNotFoundError : load_error.ptr(), e.what());
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });

  py::class_<MeshCore>(m, "MeshCore")
      .def(py::init(&MeshCore::from_arrays), py::arg("positions"), py::arg("faces"), py::arg("normals"), py::arg("uvs"),
           py::arg("colors"), py::arg("texture"), py::arg("material"))
      .def_static(
          "from_file",
          [](const std::string& path, bool allow_external_files, py::handle max_triangles, py::handle max_points,
             py::handle max_texture_size) {
            return load_mesh_file(path,
                                  load_options_of(allow_external_files, max_triangles, max_points, max_texture_size));
          },
          py::arg("path"), py::arg("allow_external_files"), py::arg("max_triangles"), py::arg("max_points"),
          py::arg("max_texture_size"))
      .def_property_readonly("vertex_count", [](const MeshCore& c) { return c.mesh->vertex_count(); })
      .def_property_readonly("triangle_count", [](const MeshCore& c) { return c.mesh->triangle_count(); })
      .def_property_readonly("point_count", [](const MeshCore& c) { return c.mesh->point_count(); })
      .def_property_readonly("bounds", &MeshCore::bounds);

  py::class_<MotionCore>(m, "MotionCore")
      .def("animations", &MotionCore::animations)
      .def("pose", &MotionCore::pose, py::arg("animation"), py::arg("seconds"));

  py::class_<SceneCore>(m, "SceneCore").def(py::init<>()).def("sync", &SceneCore::sync, py::arg("instances"));

  py::class_<RendererCore>(m, "RendererCore")
      .def(py::init<int, int, int, int>(), py::arg("width"), py::arg("height"), py::arg("threads"), py::arg("samples"))
      .def_property_readonly("width", &RendererCore::width)
      .def_property_readonly("height", &RendererCore::height)
      .def("render", &RendererCore::render)
      .def("camera_json", &RendererCore::camera);

  m.def(
      "read_model",
      [](const std::string& path, bool allow_external_files, py::handle max_triangles, py::handle max_points,
         py::handle max_texture_size) {
        return read_model_file(path,
                               load_options_of(allow_external_files, max_triangles, max_points, max_texture_size));
      },
      py::arg("path"), py::arg("allow_external_files"), py::arg("max_triangles"), py::arg("max_points"),
      py::arg("max_texture_size"));
  m.def("render_file", &render_file);
  // The load limits' defaults, for the Python keywords.
  m.attr("__version__") = FACET_VERSION;
  m.attr("DEFAULT_MAX_TRIANGLES") = facet::kDefaultMaxTriangles;
  m.attr("DEFAULT_MAX_POINTS") = facet::kDefaultMaxPoints;
  m.attr("MAX_TEXTURE_SIZE") = facet::kMaxTextureSize;
  m.attr("HEADLIGHT_FROM_CAMERA") =
      py::make_tuple(facet::kHeadlightFromCamera.x, facet::kHeadlightFromCamera.y, facet::kHeadlightFromCamera.z);
}
