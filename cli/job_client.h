#ifndef EVOSLAM_CLI_JOB_CLIENT_H_
#define EVOSLAM_CLI_JOB_CLIENT_H_

#include <filesystem>
#include <string>
#include <vector>

#include "common/service/service_client.h"
#include "evoslam/service.pb.h"

namespace evoslam::cli {

// Uploads a map: a LineMap text file as it is, a map_server YAML with its image (the YAML sent
// names the image by its base name, so both can live side by side on the coordinator).
void UploadMap(ServiceClient& client, const std::filesystem::path& map, proto::JobSpec& spec);

// Follows a job to its end with one progress bar for the whole job, scans done of its scans
// with the step under way inside it: on a terminal a bar, elsewhere a line in the log at most
// every 10 s (ProgressBar). Returns its final status.
proto::JobStatus WatchWithProgress(ServiceClient& client, const std::string& job_id);

// Follows a job to its end as WatchWithProgress does; throws Error when it failed or was
// cancelled. Returns its files.
std::vector<proto::ResultFile> FollowToResult(ServiceClient& client, const std::string& job_id,
                                              bool name_job = true);

// Writes a job's files into `dir` (created if needed).
void WriteResultFiles(const std::vector<proto::ResultFile>& files,
                      const std::filesystem::path& dir);

}  // namespace evoslam::cli

#endif  // EVOSLAM_CLI_JOB_CLIENT_H_
