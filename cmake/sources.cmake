# sources.cmake - the library's sources, once, by layer; the native build (CMakeLists.txt) and the browser build
# (web/CMakeLists.txt) both list them from here. Each layer's sources include only their own layer's headers and
# those of the layers above it in this file. FACET_SOURCE_ROOT is the checkout's root.

# The core: framebuffer, renderer, clipping, set-up and binning, the shader contract's pipeline, lanes, maths.
set(FACET_CORE_SOURCES
  ${FACET_SOURCE_ROOT}/src/clip/clip.cpp
  ${FACET_SOURCE_ROOT}/src/core/buffers.cpp
  ${FACET_SOURCE_ROOT}/src/core/framebuffer.cpp
  ${FACET_SOURCE_ROOT}/src/core/renderer.cpp
  ${FACET_SOURCE_ROOT}/src/core/text.cpp
  ${FACET_SOURCE_ROOT}/src/core/thread_pool.cpp
  ${FACET_SOURCE_ROOT}/src/core/warnings.cpp
  ${FACET_SOURCE_ROOT}/src/math/camera.cpp
  ${FACET_SOURCE_ROOT}/src/math/projection.cpp
  ${FACET_SOURCE_ROOT}/src/math/transform.cpp
  ${FACET_SOURCE_ROOT}/src/setup/cull.cpp
  ${FACET_SOURCE_ROOT}/src/setup/project.cpp
  ${FACET_SOURCE_ROOT}/src/setup/setup.cpp
  ${FACET_SOURCE_ROOT}/src/setup/setup_lanes.cpp)

# The scene: meshes, textures, materials, lights and environments, the stock shaders' pipelines, and the scene
# that draws instances with them.
set(FACET_SCENE_SOURCES
  ${FACET_SOURCE_ROOT}/src/lighting/brdf_table.cpp
  ${FACET_SOURCE_ROOT}/src/lighting/environment.cpp
  ${FACET_SOURCE_ROOT}/src/lighting/studio.cpp
  ${FACET_SOURCE_ROOT}/src/mesh/mesh.cpp
  ${FACET_SOURCE_ROOT}/src/mesh/model.cpp
  ${FACET_SOURCE_ROOT}/src/mesh/primitives.cpp
  ${FACET_SOURCE_ROOT}/src/mesh/topology.cpp
  ${FACET_SOURCE_ROOT}/src/scene/ambient_occlusion.cpp
  ${FACET_SOURCE_ROOT}/src/scene/demo_scenes.cpp
  ${FACET_SOURCE_ROOT}/src/scene/draw.cpp
  ${FACET_SOURCE_ROOT}/src/scene/look.cpp
  ${FACET_SOURCE_ROOT}/src/scene/prepare.cpp
  ${FACET_SOURCE_ROOT}/src/scene/scene.cpp
  ${FACET_SOURCE_ROOT}/src/scene/shadows.cpp
  ${FACET_SOURCE_ROOT}/src/scene/surface_ids.cpp
  ${FACET_SOURCE_ROOT}/src/shaders/lit_instances.cpp
  ${FACET_SOURCE_ROOT}/src/shaders/masked_instances.cpp
  ${FACET_SOURCE_ROOT}/src/shaders/pbr_instance.cpp
  ${FACET_SOURCE_ROOT}/src/shaders/plain_instances.cpp
  ${FACET_SOURCE_ROOT}/src/shaders/surface_instance.cpp
  ${FACET_SOURCE_ROOT}/src/shaders/tangent_pbr_instance.cpp
  ${FACET_SOURCE_ROOT}/src/shaders/untextured_pbr_instance.cpp
  ${FACET_SOURCE_ROOT}/src/shaders/untextured_surface_instance.cpp
  ${FACET_SOURCE_ROOT}/src/texture/image_decode.cpp
  ${FACET_SOURCE_ROOT}/src/texture/sampling.cpp
  ${FACET_SOURCE_ROOT}/src/texture/texture.cpp)

# The job: facet's own model and environment readers and the view specifications, which run everywhere.
set(FACET_JOB_SOURCES
  ${FACET_SOURCE_ROOT}/src/io/environment_io.cpp
  ${FACET_SOURCE_ROOT}/src/io/file_util.cpp
  ${FACET_SOURCE_ROOT}/src/io/gltf_draco.cpp
  ${FACET_SOURCE_ROOT}/src/io/gltf_lights.cpp
  ${FACET_SOURCE_ROOT}/src/io/gltf_loader.cpp
  ${FACET_SOURCE_ROOT}/src/io/gltf_material.cpp
  ${FACET_SOURCE_ROOT}/src/io/gltf_meshopt.cpp
  ${FACET_SOURCE_ROOT}/src/io/model_io.cpp
  ${FACET_SOURCE_ROOT}/src/io/obj_loader.cpp
  ${FACET_SOURCE_ROOT}/src/io/obj_parse.cpp
  ${FACET_SOURCE_ROOT}/src/io/ply_header.cpp
  ${FACET_SOURCE_ROOT}/src/io/ply_loader.cpp
  ${FACET_SOURCE_ROOT}/src/io/references.cpp
  ${FACET_SOURCE_ROOT}/src/io/stl_loader.cpp
  ${FACET_SOURCE_ROOT}/src/scene/view_spec.cpp)

# The job's parts that need the host: libraries opened or linked at run time (Assimp, OpenEXR, FFmpeg, giflib,
# libspng), the writers of files, and the render job, sheets and output templates that write them. The browser
# build leaves them out.
set(FACET_HOST_JOB_SOURCES
  ${FACET_SOURCE_ROOT}/src/core/shared_library.cpp
  ${FACET_SOURCE_ROOT}/src/io/assimp_loader.cpp
  ${FACET_SOURCE_ROOT}/src/io/exr.cpp
  ${FACET_SOURCE_ROOT}/src/io/gif.cpp
  ${FACET_SOURCE_ROOT}/src/io/image_io.cpp
  ${FACET_SOURCE_ROOT}/src/io/output_file.cpp
  ${FACET_SOURCE_ROOT}/src/io/output_template.cpp
  ${FACET_SOURCE_ROOT}/src/io/png.cpp
  ${FACET_SOURCE_ROOT}/src/io/video.cpp
  ${FACET_SOURCE_ROOT}/src/scene/render_job.cpp
  ${FACET_SOURCE_ROOT}/src/scene/sheet_views.cpp)
