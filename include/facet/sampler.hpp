// sampler.hpp - how a texture is filtered and wrapped, as OpenGL's sampler state says it.
#pragma once

namespace facet {

// Filter::nearest = GL_NEAREST, bilinear = GL_LINEAR (neither uses mipmaps), trilinear = GL_LINEAR_MIPMAP_LINEAR
// for minification and GL_LINEAR for magnification.
enum class Filter { nearest, bilinear, trilinear };
// repeat = GL_REPEAT, clamp = GL_CLAMP_TO_EDGE, mirror = GL_MIRRORED_REPEAT.
enum class Wrap { repeat, clamp, mirror };

struct Sampler {
  Filter filter = Filter::trilinear;
  Wrap wrap_u = Wrap::repeat, wrap_v = Wrap::repeat;
};

}  // namespace facet
