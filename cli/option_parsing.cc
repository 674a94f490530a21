#include "cli/option_parsing.h"

#include <charconv>
#include <cmath>
#include <vector>

#include "common/util/error.h"

namespace evoslam::cli {

Pose2 ParsePose(const std::string& text, const std::string& flag) {
  std::vector<double> values;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    double v = 0;
    const auto [ptr, ec] = std::from_chars(text.data() + begin, text.data() + end, v);
    if (ec != std::errc() || ptr != text.data() + end || !std::isfinite(v)) {
      throw Error(flag + ": expected x,y,theta (three numbers), got '" + text + "'");
    }
    values.push_back(v);
    begin = end + 1;
  }
  if (values.size() != 3)
    throw Error(flag + ": expected x,y,theta (three numbers), got '" + text + "'");
  return Pose2(values[0], values[1], values[2]);
}

}  // namespace evoslam::cli
