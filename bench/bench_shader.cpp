// bench_shader.cpp - the pipeline compiled for the benchmark shader, once for every program that draws with it.
#include "facet/draw.hpp"
#include "bench/bench_shader.hpp"

FACET_INSTANTIATE_SHADER(facet::bench::BenchShader);
