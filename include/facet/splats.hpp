// splats.hpp - 3D Gaussian splats as the 3D Gaussian Splatting paper trains them, and their rasterizer.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace facet {

class Framebuffer;
class Renderer;
struct View;

// A scene of anisotropic 3D Gaussians, with the paper's activations already applied: each Gaussian's covariance is
// R S S^T R^T, R its rotation and S = diag(scale); its colour seen from direction d (centre minus eye, unit) is
// the spherical-harmonics expansion of degree sh_degree at d, plus 0.5, clamped at 0, in display values (the
// paper trains colours as they are shown: no colour-space conversion).
struct GaussianSplats {
  std::vector<glm::vec3> positions;  // centres, object space
  std::vector<glm::vec3> scales;     // standard deviations along the Gaussian's own axes (exp of the file's)
  std::vector<glm::quat> rotations;  // unit quaternions (the file's rot_0..3 as w, x, y, z, normalised)
  std::vector<float> opacities;      // 0..1 (sigmoid of the file's opacity)
  int sh_degree = 0;                 // 0..3
  // (sh_degree + 1)^2 RGB coefficients per Gaussian, Gaussian by Gaussian, the constant (DC) one first, then the
  // paper's order of the real spherical harmonics.
  std::vector<glm::vec3> sh;

  std::size_t size() const { return positions.size(); }
  std::size_t coefficients() const { return static_cast<std::size_t>((sh_degree + 1) * (sh_degree + 1)); }
};

// The degree-0 real spherical harmonic's value, 1 / (2 sqrt(pi)): a Gaussian of degree 0 shows the colour
// kShDegree0 * sh[0] + 0.5.
inline constexpr float kShDegree0 = 0.28209479177387814f;

// The most Gaussians a scene may hold (2^26: 4.3 GB of degree-3 coefficients).
inline constexpr std::size_t kMaxSplats = std::size_t{1} << 26;

// Throws InputError(source, ...) unless the arrays agree in size with positions, the degree lies in 0..3, the count
// is at most kMaxSplats, and every value is finite with scales >= 0, opacities in [0, 1] and unit rotations.
void check_splats(const GaussianSplats& splats, const std::string& source);

// The colour of Gaussian `index` seen along `direction` (unit, from the eye towards its centre), as the paper's
// rasterizer evaluates it.
glm::vec3 splat_color(const GaussianSplats& splats, std::size_t index, glm::vec3 direction);

// Composites the Gaussians, placed by world_from_object, over the colour `target` holds (its resolved colour, after
// Renderer::finish), as the paper's rasterizer does: each is projected to a 2D Gaussian through the Jacobian of the
// view's projection at its centre, with 0.3 pixel^2 added to its covariance; 16x16-pixel tiles list the Gaussians
// that reach them (3 standard deviations) sorted by view depth, and each pixel blends them front to back, alpha =
// min(0.99, opacity * G), skipping alphas under 1/255 and stopping before the transmittance falls under 1e-4; what
// is left of the transmittance shows the target's colour. A pixel's centre is where the Gaussian is evaluated (the
// paper's pixel coordinate i is facet's i + 0.5). Where the target keeps depth, a Gaussian whose centre lies behind
// a pixel's surface is left out there, so splats and meshes composite by depth; and a pixel the Gaussians cover at
// least half (accumulated alpha 0.5 or more) takes their blended view depth, sum(alpha T d) / sum(alpha T), as its
// depth, so that depth and masks read from the target show the splats. Gaussians with a centre behind the
// near plane, a degenerate footprint or a value that is not finite are skipped. Runs on the renderer's threads;
// the image is the same at any thread count. Throws InputError (source "splats") when the arrays disagree in size
// or the degree is outside 0..3; the values are the reader's to check (check_splats), not every frame's.
void render_splats(Renderer& renderer, Framebuffer& target, const View& view, const GaussianSplats& splats,
                   const glm::mat4& world_from_object = glm::mat4(1.0f));

}  // namespace facet
