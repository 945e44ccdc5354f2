// untextured_pbr_instance.cpp - the pipelines compiled for the physically based shader without derivatives and
// for the environment behind the model, once each.
#include "facet/draw.hpp"
#include "facet/shaders/stock.hpp"

FACET_INSTANTIATE_SHADER(facet::UntexturedPbrShader);
FACET_INSTANTIATE_SHADER(facet::EnvironmentBackgroundShader);
