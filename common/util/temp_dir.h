#ifndef EVOSLAM_COMMON_UTIL_TEMP_DIR_H_
#define EVOSLAM_COMMON_UTIL_TEMP_DIR_H_

#include <cstddef>
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

// Marks `dir` as the running process's (its id, start time and host, in a file `owner`), so that
// RemoveStaleTempDirs can tell it from the folder of a process killed before it could clean up.
void MarkTempDirOwner(const std::filesystem::path& dir);

// Removes the folders `prefix`-XXXXXX under the temporary directory that MarkTempDirOwner marked
// for a process no longer running (a pid reused since counts as not running); returns how many.
// Folders without the mark are left alone: another process may be about to mark its own.
std::size_t RemoveStaleTempDirs(std::string_view prefix);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_UTIL_TEMP_DIR_H_
