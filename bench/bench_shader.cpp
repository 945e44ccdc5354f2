// bench_shader.cpp - the pipeline compiled for the benchmark shader, once for every program that draws with it.
#include "bench/bench_shader.hpp"
#include "facet/draw.hpp"

FACET_INSTANTIATE_SHADER(facet::bench::BenchShader);
