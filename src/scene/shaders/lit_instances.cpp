// lit_instances.cpp - the pipeline compiled for the per-vertex and per-face lit shaders, once each.
#include "facet/draw.hpp"
#include "facet/shaders/stock.hpp"

FACET_INSTANTIATE_SHADER(facet::GouraudShader);
FACET_INSTANTIATE_SHADER(facet::FlatShader);
