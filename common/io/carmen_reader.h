#ifndef EVOSLAM_COMMON_IO_CARMEN_READER_H_
#define EVOSLAM_COMMON_IO_CARMEN_READER_H_

#include <cstddef>
#include <filesystem>
#include <string>

#include "common/sensor/dataset.h"

namespace evoslam {

struct CarmenReadOptions {
  // Skip malformed lines (counting them) instead of failing on the first one.
  bool lenient = false;
};

struct CarmenReadStats {
  std::size_t lines = 0;          // lines read, comments and blanks included
  std::size_t skipped = 0;        // malformed lines skipped in lenient mode
  std::size_t first_skip_line = 0;
  std::string first_skip_reason;  // what was wrong with that line, without the file's name
};

// Reads a CARMEN text log (plain, gzip or bzip2). FLASER and ROBOTLASER1 lines become
// Dataset::scans, RLASER and ROBOTLASER2 lines Dataset::rear_scans, ODOM lines Dataset::odometry,
// PARAM lines Dataset::params, all in log order; TRUEPOS lines give the true pose of the scans
// with the same ipc_timestamp. Comments, blank lines and other messages (SYNC, NMEA-*, ...) are
// ignored. A malformed line is an InputError saying where and what was expected, unless
// options.lenient; so is a log without a single laser scan. stats, when given, receives the
// counts.
Dataset ReadCarmen(const std::filesystem::path& path, const CarmenReadOptions& options = {},
                   CarmenReadStats* stats = nullptr);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_IO_CARMEN_READER_H_
