#include "common/util/progress_bar.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

namespace evoslam {
namespace {

// Collects what a bar writes, through a POSIX memory stream.
class Captured {
 public:
  Captured() : file_(open_memstream(&data_, &size_)) {}
  ~Captured() {
    std::fclose(file_);
    std::free(data_);
  }
  Captured(const Captured&) = delete;
  Captured& operator=(const Captured&) = delete;

  std::FILE* file() { return file_; }
  std::string text() {
    std::fflush(file_);
    return std::string(data_, size_);
  }

 private:
  char* data_ = nullptr;
  std::size_t size_ = 0;
  std::FILE* file_;
};

TEST(ProgressBarTest, DisabledWritesNothing) {
  Captured out;
  {
    ProgressBar bar("job", 10, false, out.file());
    std::this_thread::sleep_for(std::chrono::milliseconds(1100));
    bar.Update(5);
  }
  EXPECT_EQ(out.text(), "");
}

TEST(ProgressBarTest, DrawsOnlyAfterASecondAndClearsAtTheEnd) {
  Captured out;
  {
    ProgressBar bar("localize", 10, true, out.file());
    bar.Update(1);
    EXPECT_EQ(out.text(), "") << "short runs stay quiet";
    std::this_thread::sleep_for(std::chrono::milliseconds(1100));
    bar.Update(3);
    const std::string drawn = out.text();
    EXPECT_NE(drawn.find("localize ["), std::string::npos) << drawn;
    EXPECT_NE(drawn.find("3/10"), std::string::npos) << drawn;
    EXPECT_NE(drawn.find(" 30%"), std::string::npos) << drawn;
    EXPECT_NE(drawn.find("#########....................."), std::string::npos) << drawn;
  }
  const std::string all = out.text();
  EXPECT_EQ(all.substr(all.size() - 4), "\r\033[K") << "the line is cleared";
}

TEST(ProgressBarTest, ThrottlesRedrawsButAlwaysDrawsTheEnd) {
  Captured out;
  ProgressBar bar("job", 100, true, out.file());
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  bar.Update(1);
  const std::size_t after_first = out.text().size();
  bar.Update(2);  // within 100 ms of the last draw: skipped
  EXPECT_EQ(out.text().size(), after_first);
  bar.Update(100);  // completion is always shown
  EXPECT_NE(out.text().find("100/100"), std::string::npos);
}

TEST(ProgressBarTest, QuietUnderCi) {
  const char* before = std::getenv("CI");
  const std::string saved = before ? before : "";
  ::setenv("CI", "true", 1);
  EXPECT_FALSE(ProgressBar::ShouldDraw());
  if (before) {
    ::setenv("CI", saved.c_str(), 1);
  } else {
    ::unsetenv("CI");
  }
}

}  // namespace
}  // namespace evoslam
