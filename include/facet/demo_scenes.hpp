// demo_scenes.hpp - the source documents' demos (spinning cube and torus, two cubes, pentagon fan) as scenes.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "facet/mesh.hpp"
#include "facet/named.hpp"
#include "facet/scene.hpp"

namespace facet {

enum class Demo {
  cube,       // "Barebones 3D rendering with WebGL": the colour cube, spinning
  torus,      // the same motion with a lit torus
  two_cubes,  // "Computer Graphics from Scratch": two cubes seen at an angle (hidden surface removal)
  pentagon,   // the CIS367 notes' pentagon triangle fan, turning face on
};

// "cube", "torus", "two-cubes", "pentagon": the names `facet demo`, `facet view --demo` and the page take.
std::span<const Named<Demo>> demo_names();
// The demo named `name`; nullopt for anything else.
std::optional<Demo> parse_demo(std::string_view name);
const char* demo_name(Demo demo);

// A demo's mesh and the look its document gives it: flat vertex and face colours unlit on white, except the torus,
// lit so that it reads as round.
struct DemoModel {
  Demo demo = Demo::cube;
  std::shared_ptr<const Mesh> mesh;
  Shading shading = Shading::unlit;
  glm::vec3 background{1.0f};
};
DemoModel make_demo(Demo demo);

// The demo at a moment of its animation, for a target of the given aspect (width / height): its instances of
// model.mesh and the view its document sets up.
struct DemoFrame {
  std::vector<Instance> instances;
  View view;
};
DemoFrame demo_frame(const DemoModel& model, double seconds, float aspect);

}  // namespace facet
