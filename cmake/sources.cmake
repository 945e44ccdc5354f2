# sources.cmake - the library's sources, once, by layer (src/core, src/scene, src/job); the native build
# (CMakeLists.txt) and the browser build (web/CMakeLists.txt) both list them from here, the lowest layer first.
# Paths are relative to FACET_SOURCE_ROOT, the checkout's root, which the end of this file prepends.

# The core: framebuffer, renderer, clipping, set-up and binning, the shader contract's pipeline, lanes, maths.
set(FACET_CORE_SOURCES
  src/core/buffers.cpp
  src/core/cpu_level.cpp
  src/core/file_util.cpp
  src/core/clip/clip.cpp
  src/core/framebuffer.cpp
  src/core/math/camera.cpp
  src/core/math/projection.cpp
  src/core/math/transform.cpp
  src/core/raster_visibility.cpp
  src/core/renderer.cpp
  src/core/setup/cull.cpp
  src/core/setup/project.cpp
  src/core/setup/setup.cpp
  src/core/setup/setup_lanes.cpp
  src/core/text.cpp
  src/core/thread_pool.cpp
  src/core/warnings.cpp)

# The scene: meshes, textures, materials, lights and environments, the stock shaders' pipelines, and the scene
# that draws instances with them.
set(FACET_SCENE_SOURCES
  src/scene/ambient_occlusion.cpp
  src/scene/demo_scenes.cpp
  src/scene/draw.cpp
  src/scene/eye_dome_lighting.cpp
  src/scene/lighting/brdf_table.cpp
  src/scene/lighting/environment.cpp
  src/scene/lighting/studio.cpp
  src/scene/mesh/animation.cpp
  src/scene/mesh/crease_normals.cpp
  src/scene/mesh/mesh.cpp
  src/scene/mesh/model.cpp
  src/scene/mesh/pose.cpp
  src/scene/mesh/primitives.cpp
  src/scene/mesh/topology.cpp
  src/scene/prepare.cpp
  src/scene/scene.cpp
  src/scene/screen_motion.cpp
  src/scene/shaders/lit_instances.cpp
  src/scene/shaders/masked_instances.cpp
  src/scene/shaders/pbr_instance.cpp
  src/scene/shaders/plain_instances.cpp
  src/scene/shaders/surface_instance.cpp
  src/scene/shaders/tangent_pbr_instance.cpp
  src/scene/shaders/untextured_pbr_instance.cpp
  src/scene/shaders/untextured_surface_instance.cpp
  src/scene/shadows.cpp
  src/scene/splats.cpp
  src/scene/surface_ids.cpp
  src/scene/texture/image_decode.cpp
  src/scene/texture/sampling.cpp
  src/scene/texture/texture.cpp)

# The job: facet's own model and environment readers and the view specifications, which run everywhere.
set(FACET_JOB_SOURCES
  src/job/io/environment_io.cpp
  src/job/io/gltf_animation.cpp
  src/job/io/gltf_draco.cpp
  src/job/io/gltf_lights.cpp
  src/job/io/gltf_loader.cpp
  src/job/io/gltf_material.cpp
  src/job/io/gltf_meshopt.cpp
  src/job/io/model_io.cpp
  src/job/io/obj_loader.cpp
  src/job/io/obj_parse.cpp
  src/job/io/ply_header.cpp
  src/job/io/ply_loader.cpp
  src/job/io/splat_loader.cpp
  src/job/io/references.cpp
  src/job/io/stl_loader.cpp
  src/job/io/xyz_loader.cpp
  src/job/io/pcd_loader.cpp
  src/job/job_frame.cpp
  src/job/look.cpp
  src/job/names.cpp
  src/job/view_spec.cpp)

# The job's parts that need the host: libraries opened or linked at run time (Assimp, OpenEXR, FFmpeg, giflib,
# libspng), the writers of files, and the render job, sheets and output templates that write them. The browser
# build leaves them out.
set(FACET_HOST_JOB_SOURCES
  src/job/animation.cpp
  src/job/io/assimp_animation.cpp
  src/job/io/assimp_loader.cpp
  src/job/io/exr.cpp
  src/job/io/gif.cpp
  src/job/io/image_io.cpp
  src/job/io/output_file.cpp
  src/job/io/output_template.cpp
  src/job/io/png.cpp
  src/job/io/video.cpp
  src/job/render_job.cpp
  src/job/shared_library.cpp
  src/job/sheet_views.cpp
  src/job/thumbnail.cpp)

foreach(layer FACET_CORE_SOURCES FACET_SCENE_SOURCES FACET_JOB_SOURCES FACET_HOST_JOB_SOURCES)
  list(TRANSFORM ${layer} PREPEND ${FACET_SOURCE_ROOT}/)
endforeach()
