#include "common/sim/route_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

void WriteText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

TEST(RouteFileTest, ReadsWaypointsInOrderSkippingComments) {
  const TempDir dir;
  const std::filesystem::path path = dir / "loop.route";
  WriteText(path, "# two laps\n1 1\n\n 29 1.5  # corner\r\n-2e-1 +3\n");
  EXPECT_THAT(ReadRoute(path), ElementsAre(Eigen::Vector2d(1, 1), Eigen::Vector2d(29, 1.5),
                                           Eigen::Vector2d(-0.2, 3)));
}

TEST(RouteFileTest, MalformedRoutesNameFileAndLine) {
  const struct {
    std::string text;
    std::string expected;
  } cases[] = {
      {"1 1\n2 2 3\n", ":2: expected a waypoint as 2 numbers \"x y\", found 3 fields"},
      {"1\n", ":1: expected a waypoint as 2 numbers"},
      {"# c\n1 1\nnorth 2\n", ":3: x is \"north\", expected a finite number"},
      {"1 nan\n2 2\n", ":1: y is \"nan\", expected a finite number"},
      {"1 1\n", ":1: a route needs at least two waypoints, found 1"},
      {"# nothing\n\n", ":2: a route needs at least two waypoints, found 0"},
  };
  const TempDir dir;
  int i = 0;
  for (const auto& c : cases) {
    const std::filesystem::path path = dir / ("bad" + std::to_string(i++) + ".route");
    WriteText(path, c.text);
    try {
      ReadRoute(path);
      ADD_FAILURE() << "no error for " << c.text;
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(path.string() + c.expected)) << c.text;
    }
  }
}

TEST(RouteFileTest, MissingFileNamesPath) {
  const TempDir dir;
  const std::filesystem::path path = dir / "absent.route";
  try {
    ReadRoute(path);
    ADD_FAILURE() << "no error for a missing file";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path.string()));
    EXPECT_THAT(e.what(), HasSubstr("cannot open"));
  }
}

}  // namespace
}  // namespace evoslam
