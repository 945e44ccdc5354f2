// fuzz_input.hpp - what every fuzz target shares: the one outcome allowed besides success is facet's InputError.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "facet/error.hpp"

namespace facet::fuzz {

// Runs `load` on one input. InputError (and the usage errors a jobs file may raise) is the contract for bad
// input; any other exception escaping a loader is a finding, like a crash, so it aborts with its message.
template <class Load>
int run(Load&& load) {
  try {
    load();
  } catch (const InputError&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facet fuzz: unexpected exception: %s\n", e.what());
    std::abort();
  }
  return 0;
}

}  // namespace facet::fuzz
