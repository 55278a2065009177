// A folder of a test's own under the system's temporary folder, named after the process and the
// test running, empty when the test starts and removed after it.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace phonglab::test {

class TestFolder {
 public:
  // `prefix` names the suite's folders ("phonglab-document"); without `create` the folder does
  // not exist yet (what creates it is under test).
  explicit TestFolder(const std::string& prefix, bool create = true) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            (prefix + "-" + std::to_string(::getpid()) + "-" + (info != nullptr ? info->name() : "none"));
    std::filesystem::remove_all(path_);
    if (create) std::filesystem::create_directories(path_);
  }
  ~TestFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TestFolder(const TestFolder&) = delete;
  TestFolder& operator=(const TestFolder&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace phonglab::test
