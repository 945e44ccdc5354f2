// test_shaders.cpp - the pipeline compiled once for the shaders most tests draw with.
#include "support/test_shaders.hpp"
#include "facet/draw.hpp"

FACET_INSTANTIATE_SHADER(facet::test::ColorShader);
FACET_INSTANTIATE_SHADER(facet::test::TranslucentShader);
FACET_INSTANTIATE_SHADER(facet::test::CountingShader);
