#include "cli/job_client.h"

#include "common/io/file_bytes.h"
#include "common/service/dataset_files.h"
#include "common/service/job_progress.h"
#include "common/util/error.h"

namespace evoslam::cli {

void UploadMap(ServiceClient& client, const std::filesystem::path& map, proto::JobSpec& spec) {
  if (map.extension() != ".yaml" && map.extension() != ".yml") {
    *spec.mutable_map() = client.Upload(map);
    return;
  }
  const std::string yaml = ReadFileBytes(map);
  const auto image = MapYamlImage(yaml);
  if (!image || image->empty()) throw InputError(map.string(), 0, "no 'image:' key");
  std::filesystem::path image_path(*image);
  if (image_path.is_relative()) image_path = map.parent_path() / image_path;
  const proto::DatasetRef image_ref = client.Upload(image_path);
  *spec.mutable_map_image() = image_ref;
  *spec.mutable_map() =
      client.UploadBytes(map.string(), WithMapYamlImage(yaml, SafeFileName(image_ref.name())));
}

proto::JobStatus WatchWithProgress(ServiceClient& client, const std::string& job_id) {
  JobProgress progress;
  return client.Watch(job_id, [&](const proto::ProgressEvent& e) { progress.Show(e.status()); });
}

std::vector<proto::ResultFile> FollowToResult(ServiceClient& client, const std::string& job_id,
                                              bool name_job) {
  const proto::JobStatus final_status = WatchWithProgress(client, job_id);
  const std::string job = name_job ? job_id + " " : "the job ";
  if (final_status.state() == proto::JOB_STATE_FAILED) {
    throw Error(name_job ? job_id + " failed: " + final_status.error() : final_status.error());
  }
  if (final_status.state() == proto::JOB_STATE_CANCELLED) throw Error(job + "was cancelled");
  return client.Result(job_id);
}

void WriteResultFiles(const std::vector<proto::ResultFile>& files,
                      const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  for (const proto::ResultFile& f : files) {
    WriteFileBytes(dir / SafeFileName(f.name()), f.content());
  }
}

}  // namespace evoslam::cli
