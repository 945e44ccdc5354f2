// cli_options.cpp - number lists, enums, the CLI11 options, and the camera / projection flags turned into a View.
#include "cli_options.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <functional>
#include <utility>

#include "facet/camera.hpp"
#include "facet/projection.hpp"
#include "facet/transform.hpp"

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

// Runs `parse` on the option's text inside a CLI11 validator, so a malformed value is reported (exit 2) while
// parsing, before any model is loaded.
template <class Parse>
CLI::Validator parse_check(Parse parse, const std::string& description) {
  return CLI::Validator(
      [parse](std::string& value) -> std::string {
        try {
          parse(value);
        } catch (const UsageError& e) {
          // parse() names the option itself; CLI11 adds the name again, so keep only the problem.
          const std::string what = e.what();
          const auto colon = what.find(": ");
          return colon == std::string::npos ? what : what.substr(colon + 2);
        }
        return {};
      },
      description);
}

template <class E>
CLI::Option* add_enum_option(CLI::App& app, const std::string& name,
                             const std::vector<std::pair<std::string, E>>& names, std::function<void(E)> assign,
                             const std::string& description) {
  std::string choices;
  for (const auto& [text, value] : names) choices += (choices.empty() ? "" : "|") + text;
  return app
      .add_option_function<std::string>(
          name,
          [names, assign, name, choices](const std::string& text) {
            for (const auto& [candidate, value] : names)
              if (candidate == text) return assign(value);
            throw CLI::ValidationError(name, "\"" + text + "\" is not one of " + choices);
          },
          description + " (" + choices + ")")
      ->type_name("MODE");
}

// Half extents (x, y) grown to the target's aspect, with the same 8% margin frame_sphere keeps.
std::array<float, 4> fit_extents(float half_x, float half_y, float aspect) {
  const float half_h = 1.08f * std::max(half_y, half_x / aspect);
  const float half_w = half_h * aspect;
  return {-half_w, half_w, -half_h, half_h};
}

std::array<float, 4> parse_window(const std::string& text, const std::string& option) {
  const std::vector<float> v = parse_floats(text, 4, option);
  return {v[0], v[1], v[2], v[3]};
}

// The classical views, in ProjectionKind order from isometric on; oblique projects onto the front plane.
bool is_preset(ProjectionKind kind) { return kind >= ProjectionKind::isometric; }
glm::mat4 preset_rotation(ProjectionKind kind) {
  if (!is_preset(kind)) return front_view();
  using View = glm::mat4 (*)();
  constexpr View views[] = {isometric_view, dimetric_view, trimetric_view, front_view, top_view, side_view};
  return views[static_cast<int>(kind) - static_cast<int>(ProjectionKind::isometric)]();
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
  add_enum_option<ProjectionKind>(
      app, "--projection",
      {{"perspective", ProjectionKind::perspective},
       {"orthographic", ProjectionKind::orthographic},
       {"frustum", ProjectionKind::frustum},
       {"oblique", ProjectionKind::oblique},
       {"isometric", ProjectionKind::isometric},
       {"dimetric", ProjectionKind::dimetric},
       {"trimetric", ProjectionKind::trimetric},
       {"front", ProjectionKind::front},
       {"top", ProjectionKind::top},
       {"side", ProjectionKind::side}},
      [&args](ProjectionKind k) { args.projection = k; }, "Projection");
  add_floats_option(app, "--frustum", args.frustum, 4, "Frustum near-plane window L,R,B,T (glFrustum)");
  add_floats_option(app, "--ortho", args.ortho, 4, "Orthographic window L,R,B,T (default: fit the model)");
  app.add_option("--oblique-angle", args.oblique_angle, "Oblique receding direction, degrees from +X (45)")
      ->check(number_in(-1e30, 1e30))
      ->type_name("DEG");
  app.add_option("--oblique-scale", args.oblique_scale, "Oblique depth scale: 1 cavalier, 0.5 cabinet (0.5)")
      ->check(number_in(0.0, 10.0))
      ->type_name("S");
  app.add_option("--up", args.up, "The model's up axis: +Y or +Z (also -Y, -Z, +X, -X)")
      ->check(parse_check([](const std::string& v) { upright_from_model(v); }, ""))
      ->type_name("AXIS");
}

void add_look_options(CLI::App& app, LookArgs& args) {
  add_enum_option<Shading>(
      app, "--shading",
      {{"unlit", Shading::unlit},
       {"flat", Shading::flat},
       {"gouraud", Shading::gouraud},
       {"phong", Shading::phong},
       {"blinn-phong", Shading::blinn_phong},
       {"normals", Shading::normals},
       {"depth", Shading::depth}},
      [&args](Shading s) { args.shading = s; }, "Shading (default: the model's own look)");
  app.add_flag("--wireframe", args.wireframe, "Draw only the edges");
  app.add_flag("--edges", args.edges, "Draw the edges over the surfaces");
  add_enum_option<CullMode>(
      app, "--culling", {{"back", CullMode::back}, {"front", CullMode::front}, {"none", CullMode::none}},
      [&args](CullMode c) { args.culling = c; }, "Face culling (default back)");
  app.add_flag("--no-depth-test", args.no_depth_test, "Draw in submission order without the depth test");
  app.add_flag("--painter", args.painter, "Painter's algorithm: sort triangles back to front, no depth test");
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
  add_floats_option(app, "--light-direction", args.light_direction, 3,
                    "Direction towards the light, world space (default: a headlight above left)")
      ->check(parse_check(
          [](const std::string& v) {
            if (parse_vec3(v, "--light-direction") == glm::vec3(0.0f))
              throw UsageError("--light-direction: must not be zero");
          },
          ""));
  app.add_option("--threads", args.threads, "Render threads (0 = all cores)")
      ->check(number_in(0, 1024, true))
      ->type_name("N");
}

void add_output_options(CLI::App& app, OutputArgs& args, const std::string& default_resolution) {
  args.resolution = default_resolution;
  app.add_option("-o,--output", args.output, "Output PNG file")->required()->type_name("FILE");
  app.add_option("--output-depth", args.output_depth,
                 "Also write linear eye-space depth as float32 H x W .npy (0 where empty)")
      ->type_name("FILE.npy");
  app.add_option("--resolution", args.resolution, "Image size W,H (default " + default_resolution + ")")
      ->check(parse_check([](const std::string& v) { parse_resolution(v, "--resolution"); }, ""))
      ->type_name("W,H");
}

glm::mat3 upright_from_model(const std::string& up) {
  std::string axis = trim(up);
  if (axis.size() == 1) axis = "+" + axis;
  if (axis.size() == 2) axis[1] = static_cast<char>(std::toupper(static_cast<unsigned char>(axis[1])));
  // Exact columns (images of +X, +Y, +Z) rather than rotate_*() so no rounding creeps into the axes.
  const auto columns = [](glm::vec3 x, glm::vec3 y, glm::vec3 z) { return glm::mat3(x, y, z); };
  if (axis == "+Y") return glm::mat3(1.0f);
  if (axis == "-Y") return columns({-1, 0, 0}, {0, -1, 0}, {0, 0, 1});
  if (axis == "+Z") return columns({1, 0, 0}, {0, 0, -1}, {0, 1, 0});
  if (axis == "-Z") return columns({1, 0, 0}, {0, 0, 1}, {0, -1, 0});
  if (axis == "+X") return columns({0, 1, 0}, {-1, 0, 0}, {0, 0, 1});
  if (axis == "-X") return columns({0, -1, 0}, {1, 0, 0}, {0, 0, 1});
  throw UsageError("--up: expected +Y or +Z (or -Y, -Z, +X, -X), got \"" + up + "\"");
}

namespace {

View make_view_unchecked(const CameraArgs& args, glm::vec3 center, float radius, float aspect) {
  const glm::mat3 world_from_upright = glm::transpose(upright_from_model(args.up));
  const bool preset = is_preset(args.projection);
  glm::vec3 direction, up;
  if (preset || args.projection == ProjectionKind::oblique) {
    // Classical views look along the preset's axis; oblique projects onto the front plane as in CIS367.
    const glm::mat3 upright_from_eye = glm::transpose(glm::mat3(preset_rotation(args.projection)));
    direction = world_from_upright * upright_from_eye * glm::vec3(0, 0, 1);
    up = world_from_upright * upright_from_eye * glm::vec3(0, 1, 0);
  } else {
    // A 3/4 view: from +Z turned 30 degrees towards +X and lifted 20 degrees.
    const float az = glm::radians(30.0f), el = glm::radians(20.0f);
    direction = world_from_upright * glm::vec3(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
    up = world_from_upright * glm::vec3(0, 1, 0);
  }
  if (!args.view_up.empty()) up = parse_vec3(args.view_up, "--camera-view-up");
  const glm::vec3 focal = args.focal_point.empty() ? center : parse_vec3(args.focal_point, "--camera-focal-point");
  // The sphere around the focal point that still holds the whole model.
  float reach = radius + glm::distance(focal, center);
  if (!(reach > 0.0f)) reach = 1.0f;
  const bool orthographic =
      args.projection != ProjectionKind::perspective && args.projection != ProjectionKind::frustum;

  Camera camera;
  camera.view_angle_degrees = args.view_angle;
  if (!args.position.empty() && !preset && parse_vec3(args.position, "--camera-position") == focal)
    throw UsageError("--camera-position: must differ from the focal point");
  if (!args.position.empty() && !preset) {
    camera.position = parse_vec3(args.position, "--camera-position");
    camera.focal_point = focal;
    camera.view_up = up;
    const glm::vec3 forward = focal - camera.position;
    const float length = glm::length(forward);
    const float depth = length > 0.0f ? glm::dot(center - camera.position, forward / length) : 0.0f;
    const float r = std::max(radius, 1e-6f);
    camera.far = std::max(depth + 1.05f * r, 1e-3f);
    camera.near = orthographic ? depth - 1.05f * r : std::max(depth - 1.05f * r, 1e-3f * (std::abs(depth) + r));
    if (!(camera.far > camera.near)) camera.far = camera.near + 2.1f * r;
  } else {
    camera = frame_sphere(focal, reach, aspect, args.view_angle, direction, up);
  }
  if (args.azimuth != 0.0f || args.elevation != 0.0f) apply_azimuth_elevation(camera, args.azimuth, args.elevation);
  if (args.near) camera.near = *args.near;
  if (args.far) camera.far = *args.far;
  if (!orthographic && !(camera.near > 0.0f))
    throw UsageError("--near: must be positive for a perspective projection, got " + format(camera.near));
  if (!(camera.far > camera.near))
    throw UsageError("--far: must be greater than the near distance (near " + format(camera.near) + ", far " +
                     format(camera.far) + ")");

  View view;
  view.view_from_world = view_from_world(camera);
  view.near = camera.near;
  view.far = camera.far;
  switch (args.projection) {
    case ProjectionKind::perspective:
      view.clip_from_view = clip_from_view(camera, aspect);
      break;
    case ProjectionKind::frustum: {
      const float t = camera.near * std::tan(glm::radians(camera.view_angle_degrees) * 0.5f);
      const std::array<float, 4> w = args.frustum.empty() ? std::array<float, 4>{-t * aspect, t * aspect, -t, t}
                                                          : parse_window(args.frustum, "--frustum");
      view.clip_from_view = frustum(w[0], w[1], w[2], w[3], camera.near, camera.far);
      break;
    }
    case ProjectionKind::oblique: {
      const float a = glm::radians(args.oblique_angle), s = args.oblique_scale;
      // The shear turns the model's sphere into an ellipsoid reaching r * sqrt(1 + k^2) along each screen axis.
      const std::array<float, 4> w = args.ortho.empty() ? fit_extents(reach * std::hypot(1.0f, s * std::cos(a)),
                                                                      reach * std::hypot(1.0f, s * std::sin(a)), aspect)
                                                        : parse_window(args.ortho, "--ortho");
      const float pivot = glm::distance(camera.position, camera.focal_point);
      view.clip_from_view = oblique(a, s, w[0], w[1], w[2], w[3], camera.near, camera.far, pivot);
      break;
    }
    default: {
      const std::array<float, 4> w =
          args.ortho.empty() ? fit_extents(reach, reach, aspect) : parse_window(args.ortho, "--ortho");
      view.clip_from_view = ortho(w[0], w[1], w[2], w[3], camera.near, camera.far);
      break;
    }
  }
  return view;
}

}  // namespace

View make_view(const CameraArgs& args, glm::vec3 center, float radius, float aspect) {
  try {
    return make_view_unchecked(args, center, radius, aspect);
  } catch (const std::invalid_argument& e) {
    // A degenerate camera (view up along the view direction, a zero-size window, ...) is a usage error.
    throw UsageError(std::string("camera: ") + e.what());
  }
}

}  // namespace facet::cli
