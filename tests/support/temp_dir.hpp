#pragma once
// A folder of a test's own, under $TMPDIR (which ctest sets to a folder of the
// test's own: cmake/UbersimTest.cmake), named after the running GoogleTest
// test. Removed when the test passed; kept, with its path printed, when it
// failed, so that its logs can be read.
#include <gtest/gtest.h>

#include <string>

#include "temp_folder.hpp"

namespace ubersim::test {

class TempDir : public TempFolder {
 public:
  TempDir() : TempFolder(test_name(), "the failed test's files are kept in") {}
  ~TempDir() {
    if (!::testing::Test::HasFailure()) succeeded();
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

 private:
  static std::string test_name() {
    std::string name = "test";
    if (const auto* info = ::testing::UnitTest::GetInstance()->current_test_info()) {
      name = std::string(info->test_suite_name()) + "." + info->name();
    }
    for (char& c : name) {
      if (c == '/') c = '_';  // parameterized tests' names
    }
    return name;
  }
};

}  // namespace ubersim::test
