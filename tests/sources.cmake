# sources.cmake - the GoogleTest files, for tests/CMakeLists.txt and the portable build (tests/portable).
# Test files that instantiate pipelines of their own (they include facet/draw.hpp) keep the library's flags, so
# those pipelines are tested as users build them.
set(FACET_PIPELINE_TEST_SOURCES
  property/test_deferred_bench_shader.cpp
  property/test_deferred_shading.cpp
  property/test_interpolation.cpp
  property/test_lane_helpers.cpp
  property/test_surface_lanes.cpp)
# The rest draw with shaders compiled in the library or in facet_test_shaders. In an optimised build they compile
# at -O1: a third less compile time each, while the code they test keeps the library's flags. Without a compiler
# cache they share a precompiled header of GoogleTest, glm and the standard library (about 3 s of parsing per
# file); with ccache they do not, because a precompiled header differs from one checkout to the next, so ccache
# could not reuse those files' results in a fresh clone.
set(FACET_LIGHT_TEST_SOURCES
  property/test_coverage.cpp
  property/test_fast_path.cpp
  property/test_goldens.cpp
  property/test_hidden_surfaces.cpp
  property/test_multisample.cpp
  property/test_points.cpp
  property/test_occlusion_lanes.cpp
  property/test_setup_cull.cpp
  property/test_vertex_batches.cpp
  unit/test_allocations.cpp
  unit/test_animation.cpp
  unit/test_animation_job.cpp
  unit/test_assimp_animation.cpp
  unit/test_assimp_loader.cpp
  unit/test_camera.cpp
  unit/test_clear.cpp
  unit/test_clearcoat_sheen.cpp
  unit/test_clip.cpp
  unit/test_cloud_looks.cpp
  unit/test_cpu_level.cpp
  unit/test_environment_io.cpp
  unit/test_file_cameras.cpp
  unit/test_punctual_lights.cpp
  unit/test_format_parity.cpp
  unit/test_fuzz_regressions.cpp
  unit/test_gltf_animation.cpp
  unit/test_gltf_loader.cpp
  unit/test_gltf_specular.cpp
  unit/test_gltf_tangents.cpp
  unit/test_gltf_texcoord1.cpp
  unit/test_hostile_files.cpp
  unit/test_xyz_loader.cpp
  unit/test_pcd_loader.cpp
  unit/test_splat_loader.cpp
  unit/test_splats.cpp
  unit/test_image_io.cpp
  unit/test_mesh.cpp
  unit/test_names.cpp
  unit/test_model.cpp
  unit/test_obj_loader.cpp
  unit/test_obj_parse.cpp
  unit/test_output_template.cpp
  unit/test_pbr.cpp
  unit/test_ply_in_two.cpp
  unit/test_ply_loader.cpp
  unit/test_primitives.cpp
  unit/test_project.cpp
  unit/test_projection.cpp
  unit/test_render_job.cpp
  unit/test_scene.cpp
  unit/test_screen_motion.cpp
  unit/test_shared_library.cpp
  unit/test_shaders.cpp
  unit/test_simd.cpp
  unit/test_stl_loader.cpp
  unit/test_thumbnail.cpp
  unit/test_surface_buffers.cpp
  unit/test_texture.cpp
  unit/test_transform.cpp
  unit/test_vertex_lanes.cpp)
