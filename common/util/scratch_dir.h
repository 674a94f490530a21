#ifndef EVOSLAM_COMMON_UTIL_SCRATCH_DIR_H_
#define EVOSLAM_COMMON_UTIL_SCRATCH_DIR_H_

// For tests only: it asks GoogleTest which test is running.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>

namespace evoslam::testing {

// A fresh folder for the running test, removed with everything in it afterwards. The name holds
// the test's suite, its name and the process id, so that the tests ctest runs side by side, and
// two suites run at once, never share a file.
class ScratchDir {
 public:
  ScratchDir() {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "evoslam_" + std::string(info->test_suite_name()) + "_" + info->name() +
                       "_" + std::to_string(::getpid());
    // Parameterised tests are named "Prefix/Suite" and "Test/0": keep the folder one level deep.
    std::replace(name.begin(), name.end(), '/', '_');
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  std::filesystem::path operator/(std::string_view name) const { return path_ / name; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace evoslam::testing

#endif  // EVOSLAM_COMMON_UTIL_SCRATCH_DIR_H_
