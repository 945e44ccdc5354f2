// masked_instances.cpp - the pipeline compiled for the masked surface and unlit shaders (glTF alphaMode MASK).
#include "facet/draw.hpp"
#include "facet/shaders/stock.hpp"

FACET_INSTANTIATE_SHADER(facet::Masked<facet::SurfaceShader>);
FACET_INSTANTIATE_SHADER(facet::Masked<facet::UnlitShader>);
