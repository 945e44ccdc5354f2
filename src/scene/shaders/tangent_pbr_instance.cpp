// tangent_pbr_instance.cpp - the pipeline compiled for the physically based shader of meshes with tangents, once.
#include "facet/draw.hpp"
#include "facet/shaders/stock.hpp"

FACET_INSTANTIATE_SHADER(facet::TangentPbrShader);
