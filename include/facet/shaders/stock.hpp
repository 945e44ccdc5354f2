// stock.hpp - every stock shader in one include.
#pragma once

#include "facet/renderer.hpp"
#include "facet/shaders/depth.hpp"
#include "facet/shaders/environment_background.hpp"
#include "facet/shaders/flat.hpp"
#include "facet/shaders/gouraud.hpp"
#include "facet/shaders/lighting.hpp"
#include "facet/shaders/line.hpp"
#include "facet/shaders/lit.hpp"
#include "facet/shaders/masked.hpp"
#include "facet/shaders/mesh_vertex.hpp"
#include "facet/shaders/normal.hpp"
#include "facet/shaders/pbr.hpp"
#include "facet/shaders/surface.hpp"
#include "facet/shaders/surface_color.hpp"
#include "facet/shaders/unlit.hpp"

// The library compiles the pipeline for each stock shader once (src/scene/shaders/); programs link those instances.
FACET_EXTERN_SHADER(facet::SurfaceShader);
FACET_EXTERN_SHADER(facet::UntexturedSurfaceShader);
FACET_EXTERN_SHADER(facet::GouraudShader);
FACET_EXTERN_SHADER(facet::FlatShader);
FACET_EXTERN_SHADER(facet::UnlitShader);
FACET_EXTERN_SHADER(facet::NormalShader);
FACET_EXTERN_SHADER(facet::DepthShader);
FACET_EXTERN_SHADER(facet::LineShader);
FACET_EXTERN_SHADER(facet::Masked<facet::SurfaceShader>);
FACET_EXTERN_SHADER(facet::Masked<facet::UnlitShader>);
FACET_EXTERN_SHADER(facet::PbrShader);
FACET_EXTERN_SHADER(facet::UntexturedPbrShader);
FACET_EXTERN_SHADER(facet::TangentPbrShader);
FACET_EXTERN_SHADER(facet::Masked<facet::PbrShader>);
FACET_EXTERN_SHADER(facet::EnvironmentBackgroundShader);
