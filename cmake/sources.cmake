# sources.cmake - the library's sources, once, by layer; the native build (CMakeLists.txt) and the browser build
# (web/CMakeLists.txt) both list them from here, the lowest layer first. Paths are relative to FACET_SOURCE_ROOT,
# the checkout's root, which the end of this file prepends.

# The core: framebuffer, renderer, clipping, set-up and binning, the shader contract's pipeline, lanes, maths.
set(FACET_CORE_SOURCES
  src/clip/clip.cpp
  src/core/buffers.cpp
  src/core/framebuffer.cpp
  src/core/raster_visibility.cpp
  src/core/renderer.cpp
  src/core/text.cpp
  src/core/thread_pool.cpp
  src/core/warnings.cpp
  src/math/camera.cpp
  src/math/projection.cpp
  src/math/transform.cpp
  src/setup/cull.cpp
  src/setup/project.cpp
  src/setup/setup.cpp
  src/setup/setup_lanes.cpp)

# The scene: meshes, textures, materials, lights and environments, the stock shaders' pipelines, and the scene
# that draws instances with them.
set(FACET_SCENE_SOURCES
  src/lighting/brdf_table.cpp
  src/lighting/environment.cpp
  src/lighting/studio.cpp
  src/mesh/mesh.cpp
  src/mesh/model.cpp
  src/mesh/primitives.cpp
  src/mesh/topology.cpp
  src/scene/ambient_occlusion.cpp
  src/scene/demo_scenes.cpp
  src/scene/draw.cpp
  src/scene/look.cpp
  src/scene/prepare.cpp
  src/scene/scene.cpp
  src/scene/shadows.cpp
  src/scene/surface_ids.cpp
  src/shaders/lit_instances.cpp
  src/shaders/masked_instances.cpp
  src/shaders/pbr_instance.cpp
  src/shaders/plain_instances.cpp
  src/shaders/surface_instance.cpp
  src/shaders/tangent_pbr_instance.cpp
  src/shaders/untextured_pbr_instance.cpp
  src/shaders/untextured_surface_instance.cpp
  src/texture/image_decode.cpp
  src/texture/sampling.cpp
  src/texture/texture.cpp)

# The job: facet's own model and environment readers and the view specifications, which run everywhere.
set(FACET_JOB_SOURCES
  src/io/environment_io.cpp
  src/io/file_util.cpp
  src/io/gltf_draco.cpp
  src/io/gltf_lights.cpp
  src/io/gltf_loader.cpp
  src/io/gltf_material.cpp
  src/io/gltf_meshopt.cpp
  src/io/model_io.cpp
  src/io/obj_loader.cpp
  src/io/obj_parse.cpp
  src/io/ply_header.cpp
  src/io/ply_loader.cpp
  src/io/references.cpp
  src/io/stl_loader.cpp
  src/scene/names.cpp
  src/scene/view_spec.cpp)

# The job's parts that need the host: libraries opened or linked at run time (Assimp, OpenEXR, FFmpeg, giflib,
# libspng), the writers of files, and the render job, sheets and output templates that write them. The browser
# build leaves them out.
set(FACET_HOST_JOB_SOURCES
  src/core/shared_library.cpp
  src/io/assimp_loader.cpp
  src/io/exr.cpp
  src/io/gif.cpp
  src/io/image_io.cpp
  src/io/output_file.cpp
  src/io/output_template.cpp
  src/io/png.cpp
  src/io/video.cpp
  src/scene/render_job.cpp
  src/scene/sheet_views.cpp)

foreach(layer FACET_CORE_SOURCES FACET_SCENE_SOURCES FACET_JOB_SOURCES FACET_HOST_JOB_SOURCES)
  list(TRANSFORM ${layer} PREPEND ${FACET_SOURCE_ROOT}/)
endforeach()
