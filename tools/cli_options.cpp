// cli_options.cpp - number lists, enums, the CLI11 options, and the flags as the library's CameraSpec and LookSpec.
#include "cli_options.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <span>
#include <string_view>
#include <utility>

#include "facet/names.hpp"

namespace facet::cli {
namespace {

std::string format(float v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", static_cast<double>(v));
  return text;
}

std::string trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t");
  if (begin == std::string::npos) return {};
  return s.substr(begin, s.find_last_not_of(" \t") - begin + 1);
}

std::vector<std::string> split(const std::string& text, const std::string& separators) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (;;) {
    const auto end = text.find_first_of(separators, start);
    parts.push_back(trim(text.substr(start, end == std::string::npos ? std::string::npos : end - start)));
    if (end == std::string::npos) return parts;
    start = end + 1;
  }
}

// An option taking one of the library's names (facet/names.hpp); `parse` may accept more spellings than the names.
template <class E>
CLI::Option* add_enum_option(CLI::App& app, const std::string& name, std::span<const Named<E>> names,
                             std::function<void(E)> assign, const std::string& description,
                             std::function<std::optional<E>(std::string_view)> parse = {}) {
  std::string choices;
  for (const Named<E>& n : names) choices += (choices.empty() ? "" : "|") + std::string(n.name);
  if (!parse) parse = [names](std::string_view text) { return parse_name(names, text); };
  return app
      .add_option_function<std::string>(
          name,
          [parse, assign, name, choices](const std::string& text) {
            if (const std::optional<E> value = parse(text)) return assign(*value);
            throw CLI::ValidationError(name, "\"" + text + "\" is not one of " + choices);
          },
          description + " (" + choices + ")")
      ->type_name("MODE");
}

}  // namespace

std::vector<float> parse_floats(const std::string& text, std::size_t count, const std::string& option) {
  const std::vector<std::string> parts = split(text, ",");
  const auto bad = [&] {
    const std::string expected =
        count == 1 ? "a finite number" : std::to_string(count) + " comma-separated finite numbers";
    return UsageError(option + ": expected " + expected + ", got \"" + text + "\"");
  };
  if (parts.size() != count) throw bad();
  std::vector<float> values;
  for (const std::string& part : parts) {
    const char* first = part.data() + (!part.empty() && part[0] == '+' ? 1 : 0);
    float value = 0.0f;
    const auto [end, ec] = std::from_chars(first, part.data() + part.size(), value);
    if (part.empty() || ec != std::errc() || end != part.data() + part.size() || !std::isfinite(value)) throw bad();
    values.push_back(value);
  }
  return values;
}

glm::vec3 parse_vec3(const std::string& text, const std::string& option) {
  const std::vector<float> v = parse_floats(text, 3, option);
  return {v[0], v[1], v[2]};
}

CLI::Validator number_in(double lo, double hi, bool integer) {
  return CLI::Validator(
      [lo, hi, integer](std::string& value) -> std::string {
        const std::string t = trim(value);
        const char* first = t.data() + (!t.empty() && t[0] == '+' ? 1 : 0);
        double d = 0.0;
        const auto [end, ec] = std::from_chars(first, t.data() + t.size(), d);
        if (t.empty() || ec != std::errc() || end != t.data() + t.size() || !(d >= lo && d <= hi) ||
            (integer && d != std::floor(d)))
          return std::string("expected ") + (integer ? "a whole number" : "a number") + " in " +
                 format(static_cast<float>(lo)) + ".." + format(static_cast<float>(hi)) + ", got \"" + value + "\"";
        return {};
      },
      "");
}

glm::vec3 parse_color(const std::string& text, const std::string& option) {
  const glm::vec3 c = parse_vec3(text, option);
  if (glm::any(glm::lessThan(c, glm::vec3(0.0f))) || glm::any(glm::greaterThan(c, glm::vec3(1.0f))))
    throw UsageError(option + ": colour components must lie in 0..1, got \"" + text + "\"");
  return c;
}

glm::ivec2 parse_resolution(const std::string& text, const std::string& option) {
  const std::vector<std::string> parts = split(text, ",xX");
  const auto bad = [&] {
    return UsageError(option + ": expected W,H with whole numbers in 1.." + std::to_string(kMaxDimension) + ", got \"" +
                      text + "\"");
  };
  if (parts.size() != 2) throw bad();
  glm::ivec2 size;
  for (int i = 0; i < 2; ++i) {
    const std::string& part = parts[static_cast<std::size_t>(i)];
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), size[i]);
    if (part.empty() || ec != std::errc() || end != part.data() + part.size() || size[i] < 1 || size[i] > kMaxDimension)
      throw bad();
  }
  return size;
}

CLI::Option* add_floats_option(CLI::App& app, const std::string& name, std::string& target, std::size_t count,
                               const std::string& description) {
  std::string type;
  for (std::size_t i = 0; i < count; ++i) type += i ? ",N" : "N";
  return app.add_option(name, target, description)
      ->check(parse_check([count, name](const std::string& v) { parse_floats(v, count, name); }, ""))
      ->type_name(type);
}

void add_camera_options(CLI::App& app, CameraArgs& args) {
  add_floats_option(app, "--camera-position", args.position, 3,
                    "Camera position (default: frame the model from the front-right, above)");
  add_floats_option(app, "--camera-focal-point", args.focal_point, 3, "Point looked at (default: model centre)");
  add_floats_option(app, "--camera-view-up", args.view_up, 3, "Camera up direction (default: the model's up axis)");
  app.add_option("--camera-view-angle", args.view_angle, "Vertical field of view in degrees, perspective (30)")
      ->check(number_in(0.01, 179.0))
      ->type_name("DEG");
  app.add_option("--camera-azimuth-angle", args.azimuth, "Turn the camera about the view up, degrees")
      ->check(number_in(-1e30, 1e30))
      ->type_name("DEG");
  app.add_option("--camera-elevation-angle", args.elevation, "Lift the camera, degrees")
      ->check(number_in(-1e30, 1e30))
      ->type_name("DEG");
  app.add_option("--near", args.near, "Near clipping distance (default: hug the model)")
      ->check(number_in(-1e30, 1e30))
      ->type_name("N");
  app.add_option("--far", args.far, "Far clipping distance (default: hug the model)")
      ->check(number_in(-1e30, 1e30))
      ->type_name("F");
  add_enum_option<Projection>(
      app, "--projection", projection_names(), [&args](Projection k) { args.projection = k; }, "Projection");
  add_floats_option(app, "--frustum", args.frustum, 4, "Frustum near-plane window L,R,B,T (glFrustum)");
  add_floats_option(app, "--ortho", args.ortho, 4, "Orthographic window L,R,B,T (default: fit the model)");
  app.add_option("--oblique-angle", args.oblique_angle, "Oblique receding direction, degrees from +X (45)")
      ->check(number_in(-1e30, 1e30))
      ->type_name("DEG");
  app.add_option("--oblique-scale", args.oblique_scale, "Oblique depth scale: 1 cavalier, 0.5 cabinet (0.5)")
      ->check(number_in(0.0, 10.0))
      ->type_name("S");
  app.add_option("--up", args.up, "The model's up axis: +Y or +Z (also -Y, -Z, +X, -X)")
      ->check(parse_check([](const std::string& v) { parse_up(v); }, ""))
      ->type_name("AXIS");
  app.add_option("--camera-index", args.camera_index,
                 "View through the model file's camera N (glTF, in scene order; -1: frame the model)")
      ->check(number_in(-1, 1e9))
      ->type_name("N");
}

void add_lighting_options(CLI::App& app, LookArgs& args) {
  add_floats_option(app, "--light-direction", args.light_direction, 3,
                    "Direction towards the light, world space (default: a headlight above left)")
      ->check(parse_check(
          [](const std::string& v) {
            if (parse_vec3(v, "--light-direction") == glm::vec3(0.0f))
              throw UsageError("--light-direction: must not be zero");
          },
          ""));
  app.add_option("--hdri", args.hdri,
                 "Light the model's own look by this environment: an equirectangular .hdr or .exr (default: "
                 "facet's studio)")
      ->type_name("FILE");
  app.add_option("--hdri-rotation", args.hdri_rotation, "Turn the environment about the up axis (degrees)")
      ->check(number_in(-1e6, 1e6))
      ->type_name("DEG");
  app.add_flag("--hdri-background", args.hdri_background,
               "Draw the environment behind the model instead of the background colour");
  app.add_option("--hdri-blur", args.hdri_blur, "Blur the environment behind the model, 0 (sharp) to 1")
      ->check(number_in(0.0, 1.0))
      ->type_name("R");
  add_enum_option<ToneMapping>(
      app, "--tone-mapping", tone_mapping_names(), [&args](ToneMapping t) { args.tone_mapping = t; },
      "How the model's own look maps light to colour (default: neutral, Khronos PBR Neutral)");
  app.add_flag("--no-model-lights", args.no_model_lights,
               "Leave out the lights the model's file places (glTF KHR_lights_punctual) from its own look");
  app.add_flag("--shadows", args.shadows,
               "Directional and spot lights (the model's and --light-direction's) cast shadows in its own look");
  app.add_flag("--ambient-occlusion", args.ambient_occlusion,
               "Darken the environment's light in creases and contact (screen-space) in the model's own look");
  app.add_option("--exposure", args.exposure, "Scale the light of the model's own look before tone mapping (1)")
      ->check(number_in(1e-6, 1e6))
      ->type_name("X");
}

void add_look_options(CLI::App& app, LookArgs& args) {
  add_enum_option<Shading>(
      app, "--shading", shading_names(), [&args](Shading s) { args.shading = s; },
      "Shading (default: automatic, the model's own look)", parse_shading);
  app.add_flag("--wireframe", args.wireframe, "Draw only the edges");
  app.add_flag("--edges", args.edges, "Draw the edges over the surfaces");
  add_enum_option<CullMode>(
      app, "--culling", cull_mode_names(), [&args](CullMode c) { args.culling = c; },
      "Face culling (default: none, but glTF's single-sided materials cull back faces)");
  app.add_flag("--no-depth-test", args.no_depth_test, "Draw in submission order without the depth test");
  app.add_flag("--painter", args.painter, "Painter's algorithm: sort triangles back to front, no depth test");
  app.add_option("--point-size", args.point_size,
                 "Points (a point cloud's): size in pixels, at most " + std::to_string(static_cast<int>(kMaxPointSize)) +
                     " (or in the model's units, --world-point-size)")
      ->capture_default_str()
      ->check(number_in(1e-6, 1e6))
      ->type_name("S");
  app.add_flag("--world-point-size", args.world_point_size,
               "Points: --point-size in the model's units, so that nearer points look larger");
  add_enum_option<PointShape>(
      app, "--point-shape", point_shape_names(), [&args](PointShape s) { args.point_shape = s; },
      "Points: a square or a disc of --point-size pixels (default: square)");
  add_enum_option<ColorMap>(
      app, "--color-map", color_map_names(), [&args](ColorMap m) { args.color_map = m; },
      "Colour every vertex by its height along the up axis, blue (lowest) to red (highest), or by a scan's "
      "intensity, black (weakest) to white (strongest), or not (default: none)");
  app.add_option("--eye-dome-lighting", args.eye_dome_lighting,
                 "Eye-dome lighting's strength, 0 (off) to " + std::to_string(static_cast<int>(kMaxEyeDomeLighting)) +
                     " (default: " + std::to_string(static_cast<int>(kDefaultEyeDomeLighting)) +
                     " for a point cloud with neither normals nor colours, 0 otherwise)")
      ->check(number_in(0.0, kMaxEyeDomeLighting))
      ->type_name("S");
  const auto color_check = [](const std::string& name) {
    return parse_check([name](const std::string& v) { parse_color(v, name); }, "");
  };
  app.add_option("--background-color", args.background_color, "Background colour R,G,B in 0..1")
      ->check(color_check("--background-color"))
      ->type_name("R,G,B");
  app.add_flag("--no-background", args.no_background, "Transparent background (RGBA PNG)");
  app.add_option("--color", args.color, "Surface colour R,G,B in 0..1, replacing the materials' colours")
      ->check(color_check("--color"))
      ->type_name("R,G,B");
  add_lighting_options(app, args);
  app.add_option("--threads", args.threads, "Render threads (0 = all cores)")
      ->check(number_in(0, 1024, true))
      ->type_name("N");
  app.add_option("--samples", args.samples,
                 "Anti-aliasing samples per pixel: 1 (none), 2, 4 or 8 (default 4); depth, normals, ids and mask "
                 "are taken at pixel centres")
      ->check(CLI::IsMember({1, 2, 4, 8}))
      ->type_name("N");
}

void add_output_options(CLI::App& app, OutputArgs& args, const std::string& default_resolution) {
  args.resolution = default_resolution;
  app.add_option("-o,--output", args.output, "Output PNG file")->required()->type_name("FILE");
  app.add_option("--output-depth", args.output_depth,
                 "Also write linear eye-space depth: float32 H x W, .npy or .exr (0 where empty)")
      ->type_name("FILE.npy");
  app.add_option("--resolution", args.resolution, "Image size W,H (default " + default_resolution + ")")
      ->check(parse_check([](const std::string& v) { parse_resolution(v, "--resolution"); }, ""))
      ->type_name("W,H");
}

std::array<float, 4> parse_window(const std::string& text, const std::string& option) {
  const std::vector<float> v = parse_floats(text, 4, option);
  return {v[0], v[1], v[2], v[3]};
}

UpAxis parse_up(const std::string& text) {
  if (const std::optional<UpAxis> axis = parse_up_axis(text)) return *axis;
  throw UsageError("--up: expected +Y or +Z (or -Y, -Z, +X, -X), got \"" + text + "\"");
}

CameraSpec camera_spec(const CameraArgs& args) {
  CameraSpec spec;
  if (!args.position.empty()) spec.position = parse_vec3(args.position, "--camera-position");
  if (!args.focal_point.empty()) spec.focal_point = parse_vec3(args.focal_point, "--camera-focal-point");
  if (!args.view_up.empty()) spec.view_up = parse_vec3(args.view_up, "--camera-view-up");
  spec.view_angle_degrees = args.view_angle;
  spec.azimuth_degrees = args.azimuth;
  spec.elevation_degrees = args.elevation;
  spec.near = args.near;
  spec.far = args.far;
  spec.projection = args.projection;
  if (!args.frustum.empty()) spec.frustum_window = parse_window(args.frustum, "--frustum");
  if (!args.ortho.empty()) spec.ortho_window = parse_window(args.ortho, "--ortho");
  spec.oblique_angle_degrees = args.oblique_angle;
  spec.oblique_scale = args.oblique_scale;
  spec.up = parse_up(args.up);
  if (args.camera_index >= 0) spec.file_camera = args.camera_index;
  return spec;
}

void add_input_options(CLI::App& app, InputArgs& args) {
  app.add_flag("--allow-external-files", args.allow_external_files,
               "Read the files a model names (materials, textures, buffers) outside its folder too");
  app.add_option("--max-triangles", args.max_triangles,
                 "Refuse models placing more triangles (" + std::to_string(kDefaultMaxTriangles) + ")")
      ->check(CLI::Range(std::uint64_t{1}, kMostMaxTriangles))
      ->type_name("N");
  app.add_option("--max-points", args.max_points,
                 "Refuse models placing more points and Gaussian splats (" + std::to_string(kDefaultMaxPoints) + ")")
      ->check(CLI::Range(std::uint64_t{1}, kMostMaxPoints))
      ->type_name("N");
  app.add_option("--max-texture-size", args.max_texture_size,
                 "Draw untextured a material whose texture is wider or taller than N texels (" +
                     std::to_string(kMaxTextureSize) + ")")
      ->check(number_in(1, kMaxTextureSize, true))
      ->type_name("N");
}

LoadOptions load_options(const InputArgs& args) {
  return LoadOptions{.allow_external_files = args.allow_external_files,
                     .max_triangles = args.max_triangles,
                     .max_points = args.max_points,
                     .max_texture_size = args.max_texture_size};
}

LookSpec look_spec(const LookArgs& args) {
  LookSpec look;
  look.shading = args.shading;
  look.wireframe = args.wireframe;
  look.edges = args.edges;
  look.depth_test = !args.no_depth_test;
  look.painter = args.painter;
  look.cull = args.culling;
  if (!args.background_color.empty()) look.background = parse_color(args.background_color, "--background-color");
  look.transparent_background = args.no_background;
  if (!args.color.empty()) look.color = parse_color(args.color, "--color");
  if (!args.light_direction.empty()) look.light_direction = parse_vec3(args.light_direction, "--light-direction");
  look.hdri = args.hdri;
  look.hdri_rotation = args.hdri_rotation;
  look.tone_mapping = args.tone_mapping;
  look.exposure = args.exposure;
  look.hdri_background = args.hdri_background;
  look.hdri_blur = args.hdri_blur;
  look.model_lights = !args.no_model_lights;
  look.shadows = args.shadows;
  look.ambient_occlusion = args.ambient_occlusion;
  look.point_size = args.point_size;
  look.point_shape = args.point_shape;
  look.world_point_size = args.world_point_size;
  look.eye_dome_lighting = args.eye_dome_lighting;
  look.color_map = args.color_map;
  return look;
}

}  // namespace facet::cli
