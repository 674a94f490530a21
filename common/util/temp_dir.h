#ifndef EVOSLAM_COMMON_UTIL_TEMP_DIR_H_
#define EVOSLAM_COMMON_UTIL_TEMP_DIR_H_

#include <filesystem>
#include <string_view>

namespace evoslam {

// A fresh private folder under the system's temporary directory (mkdtemp), removed with
// everything in it when the object goes. Movable, not copyable.
class TempDir {
 public:
  explicit TempDir(std::string_view prefix = "evoslam");
  ~TempDir();
  TempDir(TempDir&& other) noexcept;
  TempDir& operator=(TempDir&& other) noexcept;
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(std::string_view name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_UTIL_TEMP_DIR_H_
