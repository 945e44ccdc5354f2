// info_command.cpp - `facet info`: loads a model and prints what it holds.
#include "info_command.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <utility>

#include "cli_options.hpp"
#include "facet/mesh.hpp"
#include "facet/model.hpp"
#include "facet/model_io.hpp"
#include "facet/splats.hpp"

namespace facet::cli {
namespace {

void print_vec3(const char* label, glm::vec3 v) { std::printf("%s: %g %g %g\n", label, v.x, v.y, v.z); }

const char* yes_no(bool b) { return b ? "yes" : "no"; }

// "animation 0: \"Walk\", 1.25 s, 3 channels (translation 1, rotation 2)": what --animation NAME|INDEX picks.
void print_animation(std::size_t index, const Animation& clip) {
  constexpr const char* kProperties[] = {"translation", "rotation", "scale", "weights"};
  std::size_t counts[4] = {};
  for (const AnimationChannel& c : clip.channels) ++counts[static_cast<int>(c.property)];
  std::string kinds;
  for (int p = 0; p < 4; ++p)
    if (counts[p]) kinds += (kinds.empty() ? "" : ", ") + std::string(kProperties[p]) + " " + std::to_string(counts[p]);
  std::string name = clip.name;  // a file's text: control characters and quotes are not printed as they are
  std::replace_if(
      name.begin(), name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == '"'; }, '?');
  std::printf("animation %zu: \"%s\", %g s, %zu channel%s%s\n", index, name.c_str(), clip.duration(),
              clip.channels.size(), clip.channels.size() == 1 ? "" : "s",
              kinds.empty() ? "" : (" (" + kinds + ")").c_str());
}

// The loader splits a corner wherever its uv or normal differs, so vertex indices over-count the model's own
// vertices and edges; welding by exact position counts them as the modeller sees them.
Mesh welded(const Mesh& mesh) {
  std::map<std::array<std::uint32_t, 3>, std::uint32_t> first;
  std::vector<std::uint32_t> canonical(mesh.positions.size());
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    std::array<std::uint32_t, 3> key;
    std::memcpy(key.data(), &mesh.positions[i], sizeof key);
    canonical[i] = first.try_emplace(key, static_cast<std::uint32_t>(i)).first->second;
  }
  Mesh out;
  out.positions = mesh.positions;
  out.indices.reserve(mesh.indices.size());
  for (const std::uint32_t index : mesh.indices) out.indices.push_back(canonical[index]);
  return out;
}

std::size_t distinct(const std::vector<std::uint32_t>& indices) {
  std::vector<bool> seen;
  std::size_t count = 0;
  for (const std::uint32_t i : indices) {
    if (i >= seen.size()) seen.resize(i + 1, false);
    if (!seen[i]) ++count;
    seen[i] = true;
  }
  return count;
}

}  // namespace

CLI::App* add_info_command(CLI::App& app, InfoArgs& args) {
  CLI::App* info = app.add_subcommand("info", "Print a model's vertex, triangle, edge and material counts and bounds");
  info->add_option("model", args.model, "Model file (any format facet render reads)")->required()->type_name("MODEL");
  add_input_options(*info, args.input);
  return info;
}

int run_info(const InfoArgs& args) {
  std::string format;
  Model model = read_model(args.model, format, load_options(args.input));
  const std::size_t meshes = model.meshes.size(), instances = model.instances.size();
  const std::vector<Animation> animations = model.animations;
  const std::size_t skins = model.skins.size();
  std::size_t morph_targets = 0;
  for (const MeshDeformation& d : model.deformations) morph_targets += d.morph_targets.size();
  // Drawn as `facet render` draws it: skins and morph targets at rest.
  const Mesh mesh = flatten(at_rest(std::move(model), args.model), args.model);
  const Bounds box = bounds(mesh);
  std::printf("file: %s\n", args.model.c_str());
  std::printf("format: %s\n", format.c_str());
  const Mesh weld = welded(mesh);
  // A point cloud's vertices are its points.
  std::printf("vertices: %zu\n", mesh.indices.empty() ? mesh.vertex_count() : distinct(weld.indices));
  std::printf("render vertices: %zu\n", mesh.vertex_count());
  std::printf("triangles: %zu\n", mesh.triangle_count());
  std::printf("points: %zu\n", mesh.point_count());
  std::printf("gaussian splats: %zu\n", mesh.splats ? mesh.splats->size() : 0);
  if (mesh.splats) std::printf("spherical harmonics degree: %d\n", mesh.splats->sh_degree);
  std::printf("edges: %zu\n", unique_edges(weld).size());
  std::printf("materials: %zu\n", mesh.materials.size());
  std::size_t textured = 0;
  for (const Material& m : mesh.materials) textured += m.diffuse_map || !m.diffuse_texture.empty();
  std::printf("textured materials: %zu\n", textured);
  std::printf("cameras: %zu\n", mesh.cameras.size());
  std::printf("lights: %zu\n", mesh.lights.size());
  std::printf("meshes: %zu\n", meshes);
  std::printf("instances: %zu\n", instances);
  print_vec3("bounds min", box.min);
  print_vec3("bounds max", box.max);
  print_vec3("size", box.max - box.min);
  print_vec3("center", box.center());
  std::printf("radius: %g\n", box.radius());
  std::printf("normals: %s\n", yes_no(!mesh.normals.empty()));
  std::printf("uvs: %s\n", yes_no(!mesh.uvs.empty()));
  std::printf("vertex colors: %s\n", yes_no(!mesh.colors.empty()));
  std::printf("skins: %zu\n", skins);
  std::printf("morph targets: %zu\n", morph_targets);
  std::printf("animations: %zu\n", animations.size());
  for (std::size_t i = 0; i < animations.size(); ++i) print_animation(i, animations[i]);
  return std::fflush(stdout) == 0 ? 0 : 1;
}

}  // namespace facet::cli
