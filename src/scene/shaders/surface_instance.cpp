// surface_instance.cpp - the pipeline compiled for SurfaceShader (per-pixel Phong and Blinn-Phong), once.
#include "facet/draw.hpp"
#include "facet/shaders/stock.hpp"

FACET_INSTANTIATE_SHADER(facet::SurfaceShader);
