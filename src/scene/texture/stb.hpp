// stb.hpp - the stb_image header, with the warnings its implementation raises silenced.
// The one file that compiles the implementation defines STB_IMAGE_IMPLEMENTATION (and any STBI_* options) before
// including this; every other includer gets the declarations only. PNG files are written by job/io/png.hpp.
#pragma once

// Third-party code we do not patch: without this, -Werror builds would fail inside stb.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#include <stb_image.h>
#pragma GCC diagnostic pop
