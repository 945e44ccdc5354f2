// untextured_surface_instance.cpp - the pipeline compiled for UntexturedSurfaceShader (no derivatives), once.
#include "facet/draw.hpp"
#include "facet/shaders/stock.hpp"

FACET_INSTANTIATE_SHADER(facet::UntexturedSurfaceShader);
