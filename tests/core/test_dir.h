// A fresh, empty folder per test (<tmp>/<suite>/<test name>), so tests never see each
// other's files.
#pragma once

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace photovr::testing {

inline std::filesystem::path freshTestDir(const std::string& suite) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / suite / info->name();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace photovr::testing
