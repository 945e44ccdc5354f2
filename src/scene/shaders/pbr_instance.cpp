// pbr_instance.cpp - the pipeline compiled for the physically based shader and its masked form, once each.
#include "facet/draw.hpp"
#include "facet/shaders/stock.hpp"

FACET_INSTANTIATE_SHADER(facet::PbrShader);
FACET_INSTANTIATE_SHADER(facet::Masked<facet::PbrShader>);
