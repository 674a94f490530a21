#include "common/service/dataset_files.h"

#include <utility>

#include "common/io/file_bytes.h"
#include "common/util/error.h"
#include "common/util/sha256.h"

namespace evoslam {
namespace {

void WriteAtomically(const std::filesystem::path& path, std::string_view content) {
  // Written beside and renamed, so a reader never sees half a file, even after a crash.
  const std::filesystem::path partial = path.string() + ".partial";
  WriteFileBytes(partial, content);
  std::filesystem::rename(partial, path);
}

}  // namespace

std::string SafeFileName(std::string_view name) {
  const std::size_t slash = name.find_last_of('/');
  if (slash != std::string_view::npos) name.remove_prefix(slash + 1);
  std::string safe;
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '.' || c == '-' || c == '_';
    safe += ok ? c : '_';
  }
  if (safe.empty() || safe.find_first_not_of('.') == std::string::npos) safe = "data";
  return safe.substr(0, 128);
}

void ValidateDatasetRef(const proto::DatasetRef& ref, const char* what) {
  if (!IsSha256Hex(ref.sha256())) {
    throw Error(std::string(what) + ": '" + ref.sha256().substr(0, 80) +
                "' is not a SHA-256 (64 lowercase hex digits)");
  }
}

DatasetFiles::DatasetFiles(std::filesystem::path root) : root_(std::move(root)) {
  std::filesystem::create_directories(root_);
}

std::optional<std::filesystem::path> DatasetFiles::Find(const proto::DatasetRef& ref) const {
  const std::filesystem::path path = root_ / ref.sha256() / SafeFileName(ref.name());
  if (IsSha256Hex(ref.sha256()) && std::filesystem::is_regular_file(path)) return path;
  return std::nullopt;
}

std::filesystem::path DatasetFiles::Put(const proto::DatasetRef& ref, std::string_view content) {
  ValidateDatasetRef(ref, "dataset");
  if (ref.size_bytes() != content.size()) {
    throw Error("dataset " + ref.name() + ": " + std::to_string(content.size()) +
                " bytes received, " + std::to_string(ref.size_bytes()) + " announced");
  }
  if (Sha256Hex(content) != ref.sha256()) {
    throw Error("dataset " + ref.name() + ": its bytes do not hash to " + ref.sha256());
  }
  if (auto found = Find(ref)) return *found;
  const std::filesystem::path dir = root_ / ref.sha256();
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / SafeFileName(ref.name());
  WriteAtomically(path, content);
  return path;
}

std::filesystem::path DatasetFiles::MapWithImage(const proto::DatasetRef& yaml,
                                                 const proto::DatasetRef& image) {
  const auto yaml_path = Find(yaml);
  const auto image_path = Find(image);
  if (!yaml_path || !image_path) throw Error("map " + yaml.name() + ": its files are not here");
  const std::filesystem::path dir = root_ / (yaml.sha256() + "-" + image.sha256());
  std::filesystem::create_directories(dir);
  const std::filesystem::path to_yaml = dir / yaml_path->filename();
  const std::filesystem::path to_image = dir / image_path->filename();
  if (!std::filesystem::exists(to_yaml)) std::filesystem::copy_file(*yaml_path, to_yaml);
  if (!std::filesystem::exists(to_image)) std::filesystem::copy_file(*image_path, to_image);
  return to_yaml;
}

}  // namespace evoslam
