// stock.hpp - every stock shader in one include (each header declares its pipelines the library compiles).
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
