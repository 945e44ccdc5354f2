// cpu_level.cpp - the instruction set level the dispatched hot loops run at: the CPU's best, capped by FACET_CPU.
#include "facet/cpu_level.hpp"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <stdexcept>

#include "facet/detail/dispatch.hpp"

namespace facet {
namespace {

using detail::CpuLevel;

constexpr const char* kNames[] = {"baseline", "sse4", "avx2", "avx512"};

// The highest level both this CPU and this build can run.
CpuLevel best_level() {
#if defined(FACET_DISPATCH_X86)
  __builtin_cpu_init();
  // The features each x86-64 microarchitecture level adds, as GCC's and Clang's -march=x86-64-vN enable them.
  const bool v2 = __builtin_cpu_supports("sse4.2") && __builtin_cpu_supports("popcnt") &&
                  __builtin_cpu_supports("ssse3");
  const bool v3 = v2 && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
                  __builtin_cpu_supports("bmi2") && __builtin_cpu_supports("bmi");
#if !defined(FACET_DISPATCH_NO_V4)
  const bool v4 = v3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                  __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl") &&
                  __builtin_cpu_supports("avx512cd");
  if (v4) return CpuLevel::avx512;
#endif
  if (v3) return CpuLevel::avx2;
  if (v2) return CpuLevel::sse4;
#endif
  return CpuLevel::baseline;
}

// Off x86-64 there is one level, named for the build's target.
[[maybe_unused]] const char* single_level_name() {
#if defined(__x86_64__)
  return "baseline";
#elif defined(__aarch64__)
  return "neon";
#elif defined(__wasm_simd128__)
  return "simd128";
#else
  return "portable";
#endif
}

// The cap a name asks for; false if it names no level.
bool parse_level(std::string_view name, CpuLevel& level) {
#if defined(__x86_64__)
  for (int i = 0; i < 4; ++i)
    if (name == kNames[i]) {
      level = static_cast<CpuLevel>(i);
      return true;
    }
#else
  if (name == single_level_name() || name == "baseline") {
    level = CpuLevel::baseline;
    return true;
  }
#endif
  return false;
}

std::string accepted_names() {
#if defined(__x86_64__)
  return "avx512, avx2, sse4 or baseline";
#else
  return std::string(single_level_name()) + " or baseline";
#endif
}

// What the CPU offers and what FACET_CPU asks for, found once. Sets detail::g_cpu_level.
struct LevelState {
  CpuLevel best = best_level();
  std::string variable_error;  // why FACET_CPU was refused, empty if it was not

  LevelState() {
    CpuLevel active = best;
    if (const char* variable = std::getenv("FACET_CPU")) {
      CpuLevel cap{};
      if (parse_level(variable, cap))
        active = std::min(cap, best);
      else
        variable_error = "FACET_CPU=" + std::string(variable) + ": not a CPU level; give " + accepted_names();
    }
    detail::g_cpu_level.store(static_cast<int>(active), std::memory_order_relaxed);
  }
};

LevelState& state() {
  static LevelState s;
  return s;
}

}  // namespace

std::atomic<int> detail::g_cpu_level{-1};

int detail::find_cpu_level() {
  state();
  return g_cpu_level.load(std::memory_order_relaxed);
}

void detail::check_cpu_level_variable() {
  if (!state().variable_error.empty()) throw std::invalid_argument(state().variable_error);
}

const char* cpu_level() {
  detail::check_cpu_level_variable();
#if defined(__x86_64__)
  return kNames[static_cast<int>(detail::active_cpu_level())];
#else
  return single_level_name();
#endif
}

std::vector<std::string> cpu_levels() {
#if defined(__x86_64__)
  return {kNames, kNames + static_cast<int>(state().best) + 1};
#else
  return {single_level_name()};
#endif
}

void set_cpu_level(std::string_view name) {
  CpuLevel cap{};
  if (!parse_level(name, cap))
    throw std::invalid_argument("CPU level '" + std::string(name) + "': not a level; give " + accepted_names());
  state().variable_error.clear();  // an explicit level overrides FACET_CPU's
  detail::g_cpu_level.store(static_cast<int>(std::min(cap, state().best)), std::memory_order_relaxed);
}

}  // namespace facet
