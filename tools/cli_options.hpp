// cli_options.hpp - option parsing and camera / projection / look setup shared by `facet render` and `facet demo`.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

#include "facet/model_io.hpp"
#include "facet/named.hpp"
#include "facet/render_job.hpp"
#include "facet/texture.hpp"
#include "facet/view_spec.hpp"

namespace facet::cli {

// Bad usage found after CLI11 has parsed (exit status 2); what() names the option and the problem.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "1,2,3" -> exactly `count` finite floats; throws UsageError("<option>: ...") otherwise.
std::vector<float> parse_floats(const std::string& text, std::size_t count, const std::string& option);
glm::vec3 parse_vec3(const std::string& text, const std::string& option);
// "R,G,B" with each component in 0..1.
glm::vec3 parse_color(const std::string& text, const std::string& option);
// "L,R,B,T": a projection window.
std::array<float, 4> parse_window(const std::string& text, const std::string& option);
// "+Y", "-Z", ...: the --up axis.
UpAxis parse_up(const std::string& text);
// "W,H" or "WxH", each in 1..kMaxDimension.
glm::ivec2 parse_resolution(const std::string& text, const std::string& option);

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

// A CLI11 check: one of the library's names (facet/named.hpp).
template <class T>
CLI::IsMember one_of(std::span<const Named<T>> names) {
  std::vector<std::string> accepted;
  for (const Named<T>& n : names) accepted.emplace_back(n.name);
  return CLI::IsMember(accepted);
}

// A CLI11 check: a plain decimal number in lo..hi (no nan/inf, no trailing text), whole when `integer`.
CLI::Validator number_in(double lo, double hi, bool integer = false);

// An option holding `count` comma-separated floats, checked while CLI11 parses so errors are usage errors.
CLI::Option* add_floats_option(CLI::App& app, const std::string& name, std::string& target, std::size_t count,
                               const std::string& description);

// The camera and projection flags as given (f3d's spelling where f3d has one); empty strings were not given.
struct CameraArgs {
  std::string position, focal_point, view_up;
  float view_angle = 30.0f;  // VTK's and f3d's default vertical field of view
  float azimuth = 0.0f, elevation = 0.0f;
  std::optional<float> near, far;
  Projection projection = Projection::perspective;
  std::string frustum, ortho;  // L,R,B,T
  float oblique_angle = 45.0f, oblique_scale = 0.5f;
  std::string up = "+Y";
  int camera_index = -1;  // the model file's camera N; -1: facet frames the model
};
void add_camera_options(CLI::App& app, CameraArgs& args);

// The library's description of the camera the flags state; throws UsageError naming the flag for a bad value.
CameraSpec camera_spec(const CameraArgs& args);

// The drawing and look flags, shared by render and demo.
struct LookArgs {
  std::optional<Shading> shading;
  bool wireframe = false, edges = false, no_depth_test = false, painter = false, no_background = false;
  std::optional<CullMode> culling;
  std::string background_color, color, light_direction;
  std::string hdri;
  float hdri_rotation = 0.0f;
  ToneMapping tone_mapping = ToneMapping::neutral;
  float exposure = 1.0f;
  bool hdri_background = false;
  float hdri_blur = 0.0f;
  bool no_model_lights = false;
  bool shadows = false;
  bool ambient_occlusion = false;
  float point_size = LookSpec{}.point_size;
  PointShape point_shape = LookSpec{}.point_shape;
  bool world_point_size = false;
  std::optional<float> eye_dome_lighting;
  ColorMap color_map = LookSpec{}.color_map;
  int threads = 0;
  int samples = 4;  // multisample anti-aliasing
};
void add_look_options(CLI::App& app, LookArgs& args);
// The model's own look's light alone (key light, environment, tone mapping, model lights, shadows, ambient
// occlusion): add_look_options adds them, and the viewer, whose keys switch the rest, takes them alone.
void add_lighting_options(CLI::App& app, LookArgs& args);
LookSpec look_spec(const LookArgs& args);

// What a model file may make facet read and allocate (LoadOptions), shared by render, batch, view and info.
struct InputArgs {
  bool allow_external_files = false;
  std::uint64_t max_triangles = kDefaultMaxTriangles;
  std::uint64_t max_points = kDefaultMaxPoints;
  int max_texture_size = kMaxTextureSize;
};
void add_input_options(CLI::App& app, InputArgs& args);
LoadOptions load_options(const InputArgs& args);

// The output flags: --output, --output-depth, --resolution (and, for render, --output-mask, --output-camera).
struct OutputArgs {
  std::string output, output_depth, output_normal, output_ids, output_mask, output_camera, output_motion;
  std::string resolution;
};
void add_output_options(CLI::App& app, OutputArgs& args, const std::string& default_resolution);

}  // namespace facet::cli
