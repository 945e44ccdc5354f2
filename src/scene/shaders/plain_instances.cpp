// plain_instances.cpp - the pipeline compiled for the unlit, normal, depth and line shaders, once each.
#include "facet/draw.hpp"
#include "facet/shaders/stock.hpp"

FACET_INSTANTIATE_SHADER(facet::UnlitShader);
FACET_INSTANTIATE_SHADER(facet::NormalShader);
FACET_INSTANTIATE_SHADER(facet::DepthShader);
FACET_INSTANTIATE_SHADER(facet::LineShader);
