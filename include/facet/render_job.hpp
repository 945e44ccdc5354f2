// render_job.hpp - one render as plain data (model, size, camera, look, outputs) and the function that performs it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "facet/demo_scenes.hpp"
#include "facet/framebuffer.hpp"
#include "facet/model_io.hpp"
#include "facet/renderer.hpp"
#include "facet/scene.hpp"
#include "facet/sheet_views.hpp"
#include "facet/view_spec.hpp"

namespace facet {

// A model's animation is drawn at 30 frames a second unless the job says otherwise; at most 240.
inline constexpr double kDefaultAnimationFps = 30.0;
inline constexpr double kMaxAnimationFps = 240.0;

// Colours given to every vertex (LookSpec::color_map): none (the model's own); by height along the model's up axis,
// through blue, cyan, green and yellow to red from the lowest vertex to the highest; or by intensity (a scan's
// return strength, Mesh::intensities), grey from black at the weakest to white at the strongest.
enum class ColorMap { none, height, intensity };

// The look of a render. Unset fields take the defaults of `facet render`.
struct LookSpec {
  std::optional<Shading> shading;  // default: the caller's (the model's own look for `facet render`)
  bool wireframe = false;          // draw only the edges
  bool edges = false;              // draw the edges over the surfaces
  bool depth_test = true;          // off: draw in submission order
  bool painter = false;            // sort triangles back to front instead of depth-testing them
  // Unset: the model's own, as a model viewer does: none, so open meshes show from both sides, except for the back
  // faces of materials marked single-sided (glTF doubleSided false).
  std::optional<CullMode> cull;
  std::optional<glm::vec3> background;       // RGB in 0..1; default: the caller's
  bool transparent_background = false;       // alpha 0 where nothing is drawn (RGBA PNG)
  std::optional<glm::vec3> color;            // replaces every material, vertex and face colour
  std::optional<glm::vec3> light_direction;  // towards the light, world space; default: a headlight above left
  // The physically based look (the model's own): the environment that lights it, an equirectangular .hdr or .exr
  // (empty: facet's studio), turned by hdri_rotation degrees about the up axis (+Y); exposure and tone mapping.
  std::filesystem::path hdri{};
  float hdri_rotation = 0.0f;
  ToneMapping tone_mapping = ToneMapping::neutral;
  float exposure = 1.0f;
  bool hdri_background = false;  // draw the environment behind the model instead of the background colour
  float hdri_blur = 0.0f;        // how blurred: 0 sharp to 1
  bool model_lights = true;      // the physically based look: light the model by the lights its file places too
  // Lights the caller places (world space): besides the model's and the key light in the physically based look;
  // in the classic shadings, instead of the headlight.
  std::vector<Light> lights{};
  // Set: the model is lit by `lights` alone plus this uniform ambient colour, without an environment or a
  // headlight, as pyrender lights a scene.
  std::optional<glm::vec3> ambient{};
  bool shadows = false;            // the physically based look: directional and spot lights cast shadows
  bool ambient_occlusion = false;  // the physically based look: screen-space ambient occlusion
  float point_size = 2.0f;         // points (a point cloud's): pixels, above 0 and at most kMaxPointSize
  PointShape point_shape = PointShape::square;
  bool world_point_size = false;  // point_size in the model's units instead (SceneOptions::world_point_size)
  // Eye-dome lighting's strength, 0 to kMaxEyeDomeLighting (SceneOptions::eye_dome_lighting). Unset: on
  // (kDefaultEyeDomeLighting) for a cloud with neither normals nor colours, off otherwise.
  std::optional<float> eye_dome_lighting{};
  ColorMap color_map = ColorMap::none;  // not with `color`
};

// The files a render writes; empty paths are not written.
struct OutputSpec {
  std::filesystem::path color{};   // PNG: RGB, or RGBA with a transparent background
  std::filesystem::path depth{};   // linear eye-space depth, float32 H x W (.npy, or .exr), 0 where empty
  std::filesystem::path normal{};  // camera-space unit shading normals, float32 H x W x 3 (.npy or .exr), 0 where empty
  std::filesystem::path ids{};     // uint32 H x W x 2 .npy: instance (node) id, face id; kNoSurface where empty
  std::filesystem::path mask{};    // 8-bit greyscale PNG: 255 where a surface is drawn, 0 where empty
  std::filesystem::path camera{};  // JSON: size, near, far, intrinsics and poses (camera_json in view_spec.hpp)
  // Each pixel's motion on the image to the next frame (screen_motion in scene.hpp), float32 H x W x 2 (.npy or
  // .exr): +x right, +y down, in pixels; from the model's animation at its time to 1/fps later.
  std::filesystem::path motion{};
};

// The files an OutputSpec names, the empty ones left out, in the order of its fields.
std::vector<std::filesystem::path> output_paths(const OutputSpec& outputs);

// Refuses, before anything renders, an output whose extension names a format facet does not write for it: the
// colour image and the mask are PNG (.png), depth and normals NumPy (.npy) or OpenEXR (.exr), ids .npy and the
// camera JSON (.json), in any case; an animation's colour output is .gif, .mp4 or .webm, or PNG when its name
// holds {frame}. A name with no extension (such as /dev/null, or "-" for standard output) takes the output's first
// format. Throws std::invalid_argument("<path>: ...") naming what is written there.
void check_output_formats(const OutputSpec& outputs, bool animation = false);

// Two of several renders that would write one file: their indices in the list and the path.
struct OutputClash {
  std::size_t first = 0, second = 0;
  std::filesystem::path path;
};
// The first clash between different entries of `outputs` (paths compared lexically normalised), or nullopt. A path
// named twice within one entry is render()'s to refuse.
std::optional<OutputClash> find_output_clash(std::span<const OutputSpec> outputs);

// Removes the hidden temporary files (".NAME.PID.N.tmp") that a writer killed outright (SIGKILL, power loss) left
// beside these outputs, when process PID no longer runs on this machine; returns how many. A rerun calls this
// before rendering again. Errors are ignored: the sweep only tidies.
std::size_t remove_stale_temporaries(std::span<const OutputSpec> outputs);

// A model's animation (glTF's animations: nodes moving, skins, morph targets) in a render: one moment of it, or the
// whole clip. A job without any of these draws the model unanimated, its skins and morph targets at rest.
struct AnimationSpec {
  // The animation, by name or index (find_animation); empty: the file's first, when another field asks for one.
  std::string name{};
  // Seconds into it: the one moment drawn, or where the clip starts; clamped to the clip, with a warning.
  std::optional<double> time{};
  // The whole clip, from `time` (or 0) to its end, written as a turntable is (one GIF or video, or {frame} PNGs).
  bool play = false;
  double fps = kDefaultAnimationFps;  // frames a second, 1..kMaxAnimationFps
  int frames = 0;                     // with play: this many frames, 1/fps apart; 0: as many as reach the clip's end
  // Whether the job asks for the animation at all.
  bool any() const { return !name.empty() || time.has_value() || play; }
};

// The later frame the motion buffer of one moment runs to (OutputSpec::motion): by default the model 1/fps later
// through the same view. A clip's frames run to the next frame, and ignore it.
struct MotionSpec {
  std::optional<double> time{};    // seconds into the animation, instead of 1/fps after the job's moment
  float azimuth_degrees = 0.0f;    // the later view turned from the job's (CameraSpec::azimuth_degrees)
  float elevation_degrees = 0.0f;  // and lifted (CameraSpec::elevation_degrees); not with a file's camera
  bool moves_camera() const { return azimuth_degrees != 0.0f || elevation_degrees != 0.0f; }
};

struct RenderJob {
  std::filesystem::path model;
  // A built-in demo scene (demo_scenes.hpp) instead of a model file: its own meshes, motion, camera, shading and
  // background, under the look's settings. `time` is the moment of its first frame in seconds; `frames` frames
  // follow 1/30 s apart, written as the outputs' {frame} numbers them, or as one GIF or video.
  std::optional<Demo> demo{};
  double time = 1.0;  // at 1 s the spinning cube shows three faces
  int frames = 1;
  int width = 1024, height = 768;
  CameraSpec camera;
  LookSpec look;
  OutputSpec outputs;
  // A contact sheet instead of one view: the model drawn once per view, each width x height, in a labelled grid
  // of ceil(sqrt(n)) columns, written as the colour output alone.
  std::vector<SheetView> views;
  // A turntable instead of one view: this many frames with the camera turned round the model's up axis by
  // 360 / turntable degrees each, written as the colour output (3 s a turn, at most 50 frames a second): an
  // animated GIF looping forever, H.264 in MP4 or VP9 in WebM, by the name's extension, or numbered PNG frames
  // when its name holds {frame} (output_template.hpp).
  int turntable = 0;
  // Multisample anti-aliasing: 1, 2, 4 or 8 samples per pixel, averaged into the colour image. The depth, normal,
  // id and mask outputs hold the values at each pixel's centre, never a blend: the same as with 1 sample. 4, as
  // thumbnails are expected to look; 1 draws aliased edges, a little faster.
  int samples = 4;
  // What the model file may make facet read and allocate (model_io.hpp).
  LoadOptions load;
  AnimationSpec animation;
  MotionSpec motion;
};

// The most frames a turntable or a demo's animation may have.
inline constexpr int kMaxAnimationFrames = 3600;

// Where a render's time went, in seconds, when the caller asks (facet render --timings).
struct RenderTimings {
  double load = 0;     // reading and checking the model file
  double prepare = 0;  // framing, the view, and the scene's vertex arrays, normals, edges and textures
  double draw = 0;     // clearing, drawing and finishing the frame, the second pass behind normals and ids
  double write = 0;    // every output encoded and written
};

// The background `facet render` uses when none is given: a mid blue-grey that white and dark models stand out from.
inline constexpr glm::vec3 kDefaultBackground{0.42f, 0.45f, 0.5f};

// The direction towards the headlight, in camera space (x right, y up, z towards the viewer): from above left, as
// in illustrations, so that it lights whatever side the camera looks at and gives the three faces of a box seen in
// a 3/4 view three distinct tones.
inline constexpr glm::vec3 kHeadlightFromCamera{-0.3f, 0.5f, 0.8f};

// SceneOptions for a look. `view_from_world` places the default headlight in the world; `default_shading` applies
// when the look names none; `background` picks a wireframe colour that stays visible. The physically based look
// (Shading::automatic) is lit by the look's environment, the lights the model's file places (`model_lights`,
// unless the look turns them off), and a directional key light of intensity pi (a white diffuse surface facing
// it shows white) when the look gives a light direction; the other shadings by the light direction or the
// headlight; a look with an ambient colour by its own lights and that colour alone. Environments are prefiltered
// once per process and file (environment_for). Throws std::invalid_argument for a zero light direction, a bad
// exposure or rotation or a negative ambient colour, InputError for an unreadable environment file.
SceneOptions scene_options(const LookSpec& look, const glm::mat4& view_from_world, Shading default_shading,
                           glm::vec3 background, std::span<const Light> model_lights = {}, UpAxis up = UpAxis::pos_y);

// The prefiltered environment of a look: the built-in studio, or its .hdr/.exr file read and prefiltered on first
// use and kept for the process (a batch, a turntable or a sheet prefilters each file once).
// `up` is the model's up axis (CameraSpec::up): the environment's up turns to it.
std::shared_ptr<const Environment> environment_for(const LookSpec& look, UpAxis up = UpAxis::pos_y);

// A colour the look asks for replaces the mesh's vertex and face colours too (the shaders prefer those over the
// material), so the whole model takes it. Does nothing without one.
void apply_look_color(Mesh& mesh, const LookSpec& look);
// The look's colour map (ColorMap) as the mesh's vertex colours, replacing its vertex and face colours; heights along
// `up` (CameraSpec::up). Does nothing for ColorMap::none. Throws std::invalid_argument when the look also sets a
// colour, or asks for intensity of a mesh without intensities.
void apply_color_map(Mesh& mesh, const LookSpec& look, UpAxis up);
// The eye-dome lighting a look gives a model, as loaded: the look's strength, else kDefaultEyeDomeLighting for a
// bare cloud (points, no triangles or splats, neither normals nor colours of its own), which would otherwise draw as
// one flat silhouette, else 0. What `facet render`, sheets, turntables and the viewer use.
float eye_dome_lighting_for(const LookSpec& look, const Mesh& as_loaded);

// The clear colour of a look: its background (or `fallback`), alpha 0 when transparent.
glm::vec4 clear_color(const LookSpec& look, glm::vec3 fallback);

// Which buffers draw_buffers reads back.
struct BufferRequest {
  bool color = true;
  bool depth = false;
  bool normal = false;
  bool ids = false;
  bool mask = false;
  bool motion = false;  // needs a LaterFrame
};

// The frame after the one drawn, for the motion buffer: the same scene a moment later, and its view.
struct LaterFrame {
  const Scene* scene = nullptr;
  View view;
};

// One frame's buffers, width * height pixels each, top row first; those not asked for are empty.
struct FrameBuffers {
  int width = 0, height = 0;
  std::vector<std::uint8_t> color;  // RGBA8
  std::vector<float> depth;         // linear eye-space depth, 0 where empty
  std::vector<glm::vec3> normal;    // camera-space unit shading normals, (0, 0, 0) where empty
  SurfaceIds surfaces;              // ids: the scene instance and its mesh's triangle; kNoSurface where empty
  std::vector<std::uint32_t> ids;   // ids: file_ids(), 2 per pixel
  std::vector<std::uint8_t> mask;   // 255 where a surface is drawn, 0 where empty
  std::vector<glm::vec2> motion;    // screen_motion() to the LaterFrame
};

// Clears target, draws the scene and reads back the buffers asked for, all from one frame, so a pixel is empty in
// all of them or in none. Normals and ids take a second pass (Scene::render_ids), and the depth and mask of a
// multisampled target one more, over `centres`: a one-sample framebuffer of target's size that a caller drawing
// many frames keeps (its memory is then fresh once), or, when null or of another size, one made for the frame.
// Motion needs `later`. Throws std::invalid_argument when normals, ids or motion are asked of a wireframe or edges
// look (their lines are no surface), or motion without a later frame.
FrameBuffers draw_buffers(Renderer& renderer, Framebuffer& target, Scene& scene, const View& view,
                          const SceneOptions& options, glm::vec4 clear, const BufferRequest& request,
                          Framebuffer* centres = nullptr, const LaterFrame* later = nullptr);

// Per pixel of `surfaces` (from this scene), the file's ids of the triangle seen: its mesh's Mesh::instance_id and
// Mesh::face_id, two values per pixel; kNoSurface for both where empty. What --output-ids writes. A caller that
// numbers the scene's instances itself (Python by its nodes) passes `instance_ids`, one per Scene::instances(),
// which then take the place of Mesh::instance_id.
std::vector<std::uint32_t> file_ids(const Scene& scene, const SurfaceIds& surfaces,
                                    std::span<const std::uint32_t> instance_ids = {});

// Clears, draws the scene, and writes the outputs. Normals and ids take a second pass (Scene::render_ids) over a
// framebuffer of target's size; ids name each triangle's Mesh::instance_id and Mesh::face_id. A failure writing
// any output removes those already written, so a failed render leaves no file behind. Throws as draw_buffers.
void draw_and_write(Renderer& renderer, Framebuffer& target, Scene& scene, const View& view,
                    const SceneOptions& options, glm::vec4 clear, const OutputSpec& outputs,
                    RenderTimings* timings = nullptr, const LaterFrame* later = nullptr);

// What render() draws, read back as buffers instead of written (job.outputs is ignored); `camera`, when given,
// receives camera_json of the view. Throws as render() does.
FrameBuffers render_buffers(const RenderJob& job, Renderer& renderer, const BufferRequest& request,
                            std::string* camera = nullptr);

// Loads the model, frames it, draws it and writes the outputs; with job.views, draws the contact sheet; with
// job.turntable, the turntable; with job.demo, the demo's frames. Throws std::invalid_argument for a sheet, a
// turntable or a video asked for depth, normals, ids, a mask, the camera or a file camera, for a sheet and a
// turntable at once, a sheet larger than kMaxDimension a side, a turntable or demo of more than
// kMaxAnimationFrames frames (or a video of more than 2^30 pixels in all), a demo's frames that their outputs'
// names do not number, a bad size, camera or look, two outputs on one path. Throws InputError for a bad model
// file or an output that cannot be written.
void render(const RenderJob& job, Renderer& renderer, RenderTimings* timings = nullptr);

}  // namespace facet
