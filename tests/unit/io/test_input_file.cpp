// An input file read whole, within its limits (io/input_file).
#include "tsmframe/io/input_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tsmframe/io/input_error.hpp"

namespace {

namespace fs = std::filesystem;
using tsm::io::InputError;
using tsm::io::read_input_file;

/// The reason read_input_file gives for `path` ("" if it reads it).
std::string refusal(const std::string& path, const std::string& what = "the file") {
  try {
    read_input_file(path, what);
  } catch (const InputError& e) {
    EXPECT_EQ(e.path(), "");
    return e.reason();
  }
  return "";
}

class InputFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("tsmframe-input-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(InputFile, AFileIsReadWhole) {
  std::string text(200'000, 'x');  // beyond one read's buffer
  text += "}";
  std::ofstream(dir_ / "a.json", std::ios::binary) << text;
  EXPECT_EQ(read_input_file((dir_ / "a.json").string()), text);
}

TEST_F(InputFile, WhatCannotBeReadSaysWhy) {
  EXPECT_EQ(refusal((dir_ / "missing.json").string()), "cannot open the file");
  EXPECT_EQ(refusal((dir_ / "missing.json").string(), "the study file"), "cannot open the study file");
  EXPECT_EQ(refusal(dir_.string()), "is a directory");
}

TEST_F(InputFile, ANulByteIsNoJsonText) {
  std::ofstream(dir_ / "nul.json", std::ios::binary) << std::string("{\"a\": 1}\n\0", 10);
  EXPECT_EQ(refusal((dir_ / "nul.json").string()), "holds a NUL byte (byte 10): not JSON text");
  EXPECT_EQ(refusal("/dev/zero"), "holds a NUL byte (byte 1): not JSON text");  // a device without end
}

TEST_F(InputFile, AFileBeyondTheLimitIsRefusedBeforeItIsRead) {
  const fs::path huge = dir_ / "huge.json";
  std::ofstream(huge) << "[";
  fs::resize_file(huge, static_cast<uintmax_t>(tsm::io::max_input_bytes) + 1);  // sparse: no disk, no time
  EXPECT_EQ(refusal(huge.string()).rfind("larger than 1 GiB", 0), 0u) << refusal(huge.string());
}

}  // namespace
