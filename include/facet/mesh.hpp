// mesh.hpp - indexed triangle meshes: validation, bounds, edges, smooth/crease normals, strips, fans, polygons, buffers
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "facet/light.hpp"
#include "facet/sampler.hpp"
#include "facet/texture_slots.hpp"

namespace facet {

struct GaussianSplats;

class Texture;

// How a material's alpha is used (glTF alphaMode; the other readers give opaque).
enum class AlphaMode {
  opaque,  // alpha ignored: the surface covers what is behind it
  mask,    // opaque where alpha >= alpha_cutoff, and nothing elsewhere
  blend,   // alpha-blended over what is behind it, after the opaque surfaces, farthest first
};

// A surface's look. Colours are as displayed (sRGB-encoded), as OBJ's Kd and the colours of PLY and STL files
// hold them; a glTF reader encodes glTF's linear base colour factor and vertex colours on load. The physically
// based inputs (metallic, roughness, emission, occlusion) are glTF's metallic-roughness model; the other readers
// derive them (see docs/FORMATS.md).
struct Material {
  std::string name;
  glm::vec4 diffuse{1, 1, 1, 1};  // the base colour; OBJ: Kd and, as alpha, the dissolve d; glTF: baseColorFactor
  glm::vec3 specular{0};          // OBJ: Ks (the Blinn-Phong and Phong shadings)
  float shininess = 32;           // OBJ: Ns (the Blinn-Phong and Phong shadings)
  std::string diffuse_texture;    // absolute or relative-to-the-model path, empty if none
  // A texture the loader decoded itself (glTF's embedded images); used instead of diffuse_texture when set.
  std::shared_ptr<const Texture> diffuse_map{};
  float metallic = 0.0f;   // glTF metallicFactor, in [0, 1]
  float roughness = 0.5f;  // glTF roughnessFactor, in [0, 1] (perceptual: the GGX alpha is its square)
  // glTF metallicRoughnessTexture: roughness in green, metallic in blue, multiplying the factors (linear texels).
  std::shared_ptr<const Texture> metallic_roughness_map{};
  // Emitted radiance, linear and unbounded (glTF emissiveFactor times KHR_materials_emissive_strength), times
  // emissive_map (sRGB-encoded) when there is one.
  glm::vec3 emissive{0.0f};
  std::shared_ptr<const Texture> emissive_map{};
  // glTF occlusionTexture (red channel) and its strength: how much of the environment's light reaches the surface.
  std::shared_ptr<const Texture> occlusion_map{};
  float occlusion_strength = 1.0f;
  // The dielectric's index of refraction, which sets its reflectance at normal incidence (glTF KHR_materials_ior);
  // 0 is the extension's specular-glossiness mode, reflecting fully (then specular_color_factor sets f0).
  float ior = 1.5f;
  // glTF KHR_materials_specular: the dielectric's specular strength in [0, 1] (times specular_map's alpha) and its
  // f0 colour, linear and possibly above 1 (times specular_color_map, sRGB-encoded). Metals ignore both.
  float specular_factor = 1.0f;
  std::shared_ptr<const Texture> specular_map{};
  glm::vec3 specular_color_factor{1.0f};
  std::shared_ptr<const Texture> specular_color_map{};
  // glTF KHR_materials_clearcoat: a clear varnish over the material: its strength in [0, 1] (times clearcoat_map's
  // red; 0: no coat), its roughness (times clearcoat_roughness_map's green) and its own normal map (none: the coat
  // is smooth over the geometry's normal).
  float clearcoat = 0.0f, clearcoat_roughness = 0.0f;
  std::shared_ptr<const Texture> clearcoat_map{}, clearcoat_roughness_map{}, clearcoat_normal_map{};
  float clearcoat_normal_scale = 1.0f;
  // glTF KHR_materials_sheen: the back-scattering sheen of cloth and velvet: its linear colour (times
  // sheen_color_map, sRGB-encoded; black: no sheen) and roughness (times sheen_roughness_map's alpha).
  glm::vec3 sheen_color{0.0f};
  float sheen_roughness = 0.0f;
  std::shared_ptr<const Texture> sheen_color_map{}, sheen_roughness_map{};
  // glTF KHR_materials_transmission: how much light passes through (times transmission_map's red), drawn as an
  // approximation (docs/FORMATS.md) that needs alpha_mode blend; the glTF reader sets it.
  float transmission = 0.0f;
  std::shared_ptr<const Texture> transmission_map{};
  // The textures that read the second uv set (Mesh::uvs1), as texture_slot bits; the others read the first.
  std::uint32_t uv1_maps = 0;
  // The file's filtering and wrapping for the texture (glTF samplers); unset: the scene's (SceneOptions::sampler).
  std::optional<Sampler> sampler{};
  // Drawn with its colour alone, no lighting, when the shading is Shading::automatic (glTF KHR_materials_unlit).
  bool unlit = false;
  // A tangent-space normal map (glTF normalTexture: +X along u, +Y along v, +Z out of the surface), applied by the
  // per-pixel lit shading with its x and y scaled by normal_scale; the diffuse texture's sampler filters it.
  std::shared_ptr<const Texture> normal_map{};
  float normal_scale = 1.0f;
  AlphaMode alpha_mode = AlphaMode::opaque;
  float alpha_cutoff = 0.5f;  // AlphaMode::mask
  // Seen from both sides. false (glTF doubleSided false): back faces are culled when the look leaves culling to
  // the model (SceneOptions::cull_single_sided).
  bool double_sided = true;
  // Lit as pyrender's shader lights it (the physically based shading only): the vertex colours multiply the lit
  // colour rather than the base colour (highlights and ambient light take them too), occlusion darkens every light
  // rather than the ambient (environment) light alone, and points without normals are lit as facing the eye.
  bool pyrender_lighting = false;
};

// A camera the model file defines (glTF), placed in the world by its node. Checked when it is used (file_camera_view
// in view_spec.hpp), so a file whose unused camera is malformed still loads.
struct ModelCamera {
  std::string name;
  bool perspective = true;
  float yfov_radians = 0.8f;          // perspective: the vertical field of view
  glm::vec2 magnification{1.0f};      // orthographic: half the view's width and height (glTF xmag, ymag)
  float znear = 0.1f;                 // near clipping distance
  std::optional<float> zfar;          // far clipping distance; unset: infinite (perspective only)
  glm::mat4 world_from_camera{1.0f};  // OpenGL camera axes: x right, y up, looking down -z; unit scale
};

// The id that marks "no surface" in id buffers; no face or instance may have it.
inline constexpr std::uint32_t kNoSurface = 0xFFFFFFFFu;

struct Mesh {
  std::vector<glm::vec3> positions;
  // Each optional per-vertex attribute is either empty or has exactly one entry per position.
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<glm::vec2> uvs1;  // a second set (glTF TEXCOORD_1), read by the textures Material::uv1_maps names
  // Tangents for normal maps (glTF TANGENT): xyz the unit direction of increasing u, w +1 or -1 the sign of the
  // bitangent cross(normal, tangent). Kept only beside normals; a zero tangent means "none here" (the frame is then
  // the pixel's cotangent frame, as for meshes without tangents).
  std::vector<glm::vec4> tangents;
  std::vector<glm::vec4> colors;
  // A scanner's return strength per vertex, as the file gives it (PLY `intensity`, PCD `intensity`, Leica .pts),
  // for the intensity colour map; empty or one per position.
  std::vector<float> intensities;
  std::vector<std::uint32_t> indices;        // 3 per triangle, counter-clockwise seen from the front
  // Vertices drawn as points (Renderer::draw_points), one index each: a point cloud's vertices, glTF POINTS
  // primitives. A mesh may have triangles, points or both.
  std::vector<std::uint32_t> points;
  std::int32_t point_material = -1;          // the material the points are drawn with; -1 = the default
  std::vector<glm::vec4> face_colors;        // empty or one per triangle
  std::vector<std::int32_t> face_materials;  // empty or one per triangle; -1 = no material, else into materials
  std::vector<Material> materials;
  // Where each triangle came from, for --output-ids. Empty, or one per triangle:
  std::vector<std::uint32_t> face_ids;      // the file's face number (a polygon's triangles share it); empty: t
  std::vector<std::uint32_t> instance_ids;  // the file's node (instance) the triangle was placed by; empty: 0
  // 3D Gaussian splats (facet/splats.hpp) drawn with the mesh, composited over its surfaces by depth; positions then
  // holds their centres too, which frame the model. Null for a mesh without.
  std::shared_ptr<const GaussianSplats> splats;
  std::vector<ModelCamera> cameras;         // in the order the scene's nodes place them
  std::vector<Light> lights;                // world space, in the order the scene's nodes place them

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t triangle_count() const { return indices.size() / 3; }
  std::size_t point_count() const { return points.size(); }
  // Makes every vertex a point, in order: what a point cloud's readers give.
  void points_at_every_vertex() {
    points.resize(positions.size());
    for (std::size_t i = 0; i < points.size(); ++i) points[i] = static_cast<std::uint32_t>(i);
  }
  std::uint32_t face_id(std::size_t triangle) const {
    return face_ids.empty() ? static_cast<std::uint32_t>(triangle) : face_ids[triangle];
  }
  std::uint32_t instance_id(std::size_t triangle) const { return instance_ids.empty() ? 0 : instance_ids[triangle]; }
};

// Throws InputError(source, problem) for the first inconsistency found: an attribute or per-triangle array of the
// wrong size, an index count that is not a multiple of 3, an index or point out of range (naming its position and
// value), a face material out of range, a face or instance id of kNoSurface, or a non-finite position.
void validate(const Mesh& mesh, const std::string& source);

// Axis-aligned box. A default-constructed Bounds is empty (min = +inf, max = -inf).
struct Bounds {
  glm::vec3 min{std::numeric_limits<float>::infinity()};
  glm::vec3 max{-std::numeric_limits<float>::infinity()};

  glm::vec3 center() const { return empty() ? glm::vec3(0) : (min + max) * 0.5f; }
  // Radius of the sphere around center() that encloses the whole box (half its diagonal); 0 when empty.
  float radius() const { return empty() ? 0.0f : glm::length(max - min) * 0.5f; }
  bool empty() const { return !(min.x <= max.x && min.y <= max.y && min.z <= max.z); }
};

// Bounds over ALL positions, referenced by a triangle or not (so a mesh and its bounds do not change together when
// triangles are culled or reordered). Non-finite positions are skipped.
Bounds bounds(const Mesh& mesh);

// Each undirected edge {a, b} (a < b) of the triangles once, sorted ascending; edges of repeated indices (a == b)
// are skipped. Edges are by index, so vertices duplicated at a seam give separate edges.
std::vector<std::array<std::uint32_t, 2>> unique_edges(const Mesh& mesh);

// Replaces mesh.normals with area-weighted smooth normals (BENCHMARK.md 8.3): every triangle contributes its
// unnormalised face normal (p1 - p0) x (p2 - p0) once per corner to the group of vertices at exactly that corner's
// position (equal coordinate values, so seams and split vertices get one shared normal); each vertex gets its
// group's normalised sum, or (0, 0, 1) when the sum is zero.
void compute_smooth_normals(Mesh& mesh);

// Replaces mesh.normals with normals that stay smooth across gentle bends but split at sharp edges (like VTK's
// vtkPolyDataNormals feature angle, Blender's auto smooth or three.js toCreasedNormals). Each triangle corner gets the
// area-weighted sum, normalised, of the face normals of the triangles at its position (grouped by value as in
// compute_smooth_normals) whose face normal is within crease_angle_radians of its own triangle's (with 1e-6 of slack
// on the cosine, so coplanar faces always count); so a cube's faces stay flat and a finely tessellated sphere stays
// smooth. Corners of one vertex that end up with different normals are split: the first normal keeps the vertex,
// each other one gets a copy of it (uvs and colours too, when they have one entry per vertex) appended after the
// existing vertices, and its corners are re-pointed, so the mesh stays indexed and vertices whose corners agree stay
// shared. Triangles with zero area, a non-finite normal or an index out of range change nothing and keep their
// indices; a vertex that only such triangles use gets the smooth normal at its position, or (0, 0, 1). At pi or more
// every face counts, and the sums are compute_smooth_normals' own, in its order: the same normals, nothing split.
// Time O(n log n), plus at each position (distinct face normals x triangles there) when those faces are not all
// within half the angle of their mean: small except at the apex of a sharp, finely divided cone.
void compute_crease_normals(Mesh& mesh, float crease_angle_radians);

// OpenGL GL_TRIANGLE_STRIP: triangle i uses strip[i], strip[i+1], strip[i+2], with the first two swapped for odd i
// so every triangle keeps the strip's front-face winding. Triangles with a repeated index (the degenerate ones used
// to join strips) are dropped; the rest keep their order.
std::vector<std::uint32_t> triangles_from_strip(std::span<const std::uint32_t> strip);
// OpenGL GL_TRIANGLE_FAN: (fan[0], fan[i], fan[i+1]); triangles with a repeated index are dropped.
std::vector<std::uint32_t> triangles_from_fan(std::span<const std::uint32_t> fan);

// Triangulates one planar polygon given as indices into positions, appending 3 indices per triangle to out. A convex
// polygon becomes the fan (c0 c1 c2), (c0 c2 c3), ...; a concave one is ear-clipped in the plane of its Newell
// normal, keeping its winding. Always emits n - 2 triangles for n >= 3 corners (none for fewer). Indices must be in
// range (not checked here).
void triangulate_polygon(std::span<const glm::vec3> positions, std::span<const std::uint32_t> polygon,
                         std::vector<std::uint32_t>& out);

// Geometry (positions) plus topology (polygons as corner lists, counter-clockwise seen from the front).
struct PolygonMesh {
  std::vector<glm::vec3> positions;
  std::vector<std::vector<std::uint32_t>> polygons;
};

// One triangle list for all polygons (see triangulate_polygon), polygon order kept. Throws InputError("polygon mesh",
// ...) for a polygon with fewer than 3 corners or an index out of range.
Mesh triangulate(const PolygonMesh& polygons);
// The polygons' own edge list: each undirected boundary edge once, sorted (no triangulation diagonals).
std::vector<std::array<std::uint32_t, 2>> unique_edges(const PolygonMesh& polygons);

// Where each attribute lives inside one vertex record of an interleaved buffer of 32-bit floats (like
// glVertexAttribPointer with GL_FLOAT): position 3 floats, normal 3, uv 2, colour color_components (3 or 4).
struct VertexLayout {
  std::size_t stride = 0;  // bytes from one vertex to the next
  std::size_t position_offset = 0;
  std::optional<std::size_t> color_offset, normal_offset, uv_offset;
  int color_components = 3;  // 3 = rgb with alpha 1, or 4 = rgba
};

// Reads data.size() / stride vertices (the size must be a whole number of records). With empty indices the draw
// is non-indexed (drawArrays): vertex k is index k and the vertex count must be a multiple of 3. Every attribute
// must fit inside the stride; floats are copied with memcpy, so the buffer needs no alignment. Throws
// InputError("interleaved buffer", ...) for any inconsistency and validates the result.
Mesh mesh_from_interleaved(std::span<const std::byte> data, const VertexLayout& layout,
                           std::span<const std::uint32_t> indices = {});

}  // namespace facet
