// test_shared_library.cpp - libraries opened on demand: found, or refused with the library and package named.
#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "job/shared_library.hpp"

namespace facet::shared_library_tests {
namespace {

TEST(SharedLibrary, FindsFunctionsInAnOpenedLibrary) {
  const SharedLibrary libm("libm.so.6", "libc6");
  const auto cbrt = libm.function<double (*)(double)>("cbrt");
  EXPECT_DOUBLE_EQ(cbrt(27.0), 3.0);
}

TEST(SharedLibrary, MissingLibraryAndSymbolAreNamed) {
  try {
    const SharedLibrary missing("libfacet-absent.so.9", "libfacet-absent9");
    FAIL() << "opened a library that does not exist";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("cannot load libfacet-absent.so.9 (Debian package libfacet-absent9)"), std::string::npos)
        << message;
  }
  const SharedLibrary libm("libm.so.6", "libc6");
  try {
    libm.function<void (*)()>("facet_no_such_function");
    FAIL() << "found a function that does not exist";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              "libm.so.6 has no function facet_no_such_function: another version of the library?");
  }
}

}  // namespace
}  // namespace facet::shared_library_tests
