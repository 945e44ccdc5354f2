// untextured_pbr_instance.cpp - the pipeline compiled for the physically based shader without derivatives, once.
#include "facet/draw.hpp"
#include "facet/shaders/stock.hpp"

FACET_INSTANTIATE_SHADER(facet::UntexturedPbrShader);
