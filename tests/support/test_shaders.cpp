// test_shaders.cpp - the pipeline compiled once for the shaders most tests draw with.
#include "facet/draw.hpp"
#include "support/test_shaders.hpp"

FACET_INSTANTIATE_SHADER(facet::test::ColorShader);
FACET_INSTANTIATE_SHADER(facet::test::CountingShader);
