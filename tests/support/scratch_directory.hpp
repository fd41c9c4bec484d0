#pragma once
// A test fixture with a directory of its own under the system's temporary directory, named by
// `prefix`, the process and the test, made empty before each test and removed after it: where
// the command-line tests write their models and the program its outputs.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace tsm::test {

class ScratchDirectory : public ::testing::Test {
 protected:
  explicit ScratchDirectory(std::string prefix) : prefix_(std::move(prefix)) {}

  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           (prefix_ + std::to_string(::getpid()) + "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  /// `content` as the file `name` in the directory (`indent` as nlohmann's dump: −1 on one line).
  std::string write(const std::string& name, const nlohmann::json& content, int indent = 2) {
    std::ofstream(dir_ / name) << content.dump(indent);
    return (dir_ / name).string();
  }

  std::filesystem::path dir_;

 private:
  std::string prefix_;
};

}  // namespace tsm::test
