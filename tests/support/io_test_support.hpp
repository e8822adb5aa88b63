#pragma once
// Helpers shared by the io tests: a fresh temporary folder per test, small file writers, and
// a check that a call throws IoError naming what went wrong.

#include "litamin2/io/io_error.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace litamin2::testing {

namespace fs = std::filesystem;
using litamin2::io::IoError;

inline fs::path temp_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(LITAMIN2_BINARY_DIR) / "io_test_tmp" /
                       (std::string(info->test_suite_name()) + "_" + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

inline void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

template <typename F>
void expect_io_error(F&& f, const std::string& must_contain, const std::string& also = "") {
  try {
    f();
    ADD_FAILURE() << "expected IoError containing '" << must_contain << "'";
  } catch (const IoError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(must_contain), std::string::npos) << what;
    if (!also.empty()) {
      EXPECT_NE(what.find(also), std::string::npos) << what;
    }
  }
}

}  // namespace litamin2::testing
