#ifndef EVOSLAM_COMMON_SERVICE_DATASET_FILES_H_
#define EVOSLAM_COMMON_SERVICE_DATASET_FILES_H_

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "evoslam/service.pb.h"

namespace evoslam {

// Datasets named by the SHA-256 of their bytes, kept as files because the readers read files:
// ROOT/SHA256/NAME, NAME being the base name they were uploaded under (a reader may go by its
// extension). A map_server map lives with its image, ROOT/YAML_SHA-IMAGE_SHA/{yaml,image}, so the
// YAML's relative image path resolves.
class DatasetFiles {
 public:
  explicit DatasetFiles(std::filesystem::path root);

  // Where `ref` is kept, or nullopt when it is not here yet.
  std::optional<std::filesystem::path> Find(const proto::DatasetRef& ref) const;
  // Keeps `content` as `ref` after checking its size and hash; throws Error when they do not
  // match. Returns where it is kept.
  std::filesystem::path Put(const proto::DatasetRef& ref, std::string_view content);
  // The YAML of a map placed beside its image; both must have been Put.
  std::filesystem::path MapWithImage(const proto::DatasetRef& yaml, const proto::DatasetRef& image);

  const std::filesystem::path& root() const { return root_; }

 private:
  std::filesystem::path root_;
};

// A dataset's file name made safe to use as one path component.
std::string SafeFileName(std::string_view name);

// Checks a reference from the network: a well-formed hash and a name; throws Error otherwise.
void ValidateDatasetRef(const proto::DatasetRef& ref, const char* what);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SERVICE_DATASET_FILES_H_
