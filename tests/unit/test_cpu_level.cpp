// test_cpu_level.cpp - the CPU level the hot loops run at: the levels on offer, the cap and its errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "facet/cpu_level.hpp"

namespace facet::cpu_level_tests {
namespace {

// Restores the level the test started with, whatever the test set.
struct LevelGuard {
  std::string saved = cpu_level();
  ~LevelGuard() { set_cpu_level(saved); }
};

TEST(CpuLevel, TheActiveLevelIsOneOnOffer) {
  const std::vector<std::string> levels = cpu_levels();
  ASSERT_FALSE(levels.empty());
  EXPECT_NE(std::find(levels.begin(), levels.end(), cpu_level()), levels.end()) << cpu_level();
#if defined(__x86_64__)
  EXPECT_EQ(levels.front(), "baseline");
  const std::vector<std::string> order = {"baseline", "sse4", "avx2", "avx512"};
  for (std::size_t i = 0; i < levels.size(); ++i) EXPECT_EQ(levels[i], order[i]);  // lowest first, none skipped
#endif
}

TEST(CpuLevel, EachLevelOnOfferCanBeSetAndLevelsAboveCapNothing) {
  const LevelGuard guard;
  const std::vector<std::string> levels = cpu_levels();
  for (const std::string& level : levels) {
    set_cpu_level(level);
    EXPECT_EQ(cpu_level(), level);
  }
#if defined(__x86_64__)
  // Above the best on offer, a cap leaves the best.
  set_cpu_level("avx512");
  EXPECT_EQ(cpu_level(), levels.back());
  set_cpu_level("baseline");
  EXPECT_EQ(cpu_level(), std::string("baseline"));
#endif
}

TEST(CpuLevel, AnUnknownNameIsRefusedAndNamesTheLevels) {
  const LevelGuard guard;
  const std::string before = cpu_level();
  for (const char* name : {"", "AVX2", "avx-512", "sse2", "x86-64-v3", "avx2 "}) {
    try {
      set_cpu_level(name);
      ADD_FAILURE() << "'" << name << "' accepted";
    } catch (const std::invalid_argument& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(std::string("'") + name + "'"), std::string::npos) << message;
      EXPECT_NE(message.find("baseline"), std::string::npos) << message;
    }
    EXPECT_EQ(cpu_level(), before) << "a refused name changed the level";
  }
}

}  // namespace
}  // namespace facet::cpu_level_tests
