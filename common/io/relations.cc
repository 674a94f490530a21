#include "common/io/relations.h"

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <string_view>

#include "common/io/line_reader.h"
#include "common/io/text_fields.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

constexpr std::size_t kFields = 8;
constexpr const char* kFieldNames[kFields] = {"t1", "t2", "x", "y", "z", "roll", "pitch", "yaw"};

}  // namespace

std::vector<Relation> ReadRelations(const std::filesystem::path& path) {
  LineReader reader(path);
  std::vector<Relation> relations;
  std::vector<std::string_view> fields;
  while (const std::optional<std::string_view> line = reader.Next()) {
    SplitFields(*line, &fields);
    if (fields.empty() || fields[0].front() == '#') continue;
    if (fields.size() != kFields) {
      throw InputError(
          reader.source(), reader.line_number(),
          fmt::format("expected 8 fields (t1 t2 x y z roll pitch yaw), found {}", fields.size()));
    }
    double values[kFields];
    for (std::size_t i = 0; i < kFields; ++i) {
      const std::optional<double> value = ParseDouble(fields[i]);
      if (!value || !std::isfinite(*value)) {
        throw InputError(
            reader.source(), reader.line_number(),
            fmt::format("{} is '{}', expected a finite number", kFieldNames[i], fields[i]));
      }
      values[i] = *value;
    }
    relations.push_back({values[0], values[1], Pose2(values[2], values[3], values[7])});
  }
  return relations;
}

}  // namespace evoslam
