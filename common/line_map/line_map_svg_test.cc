#include "common/line_map/line_map_svg.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

using ::testing::HasSubstr;

std::string ReadAll(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

int Count(const std::string& text, const std::string& needle) {
  int n = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos;
       at = text.find(needle, at + 1)) {
    ++n;
  }
  return n;
}

TEST(LineMapSvgTest, DrawsWallsAndPolylinesWithYUp) {
  // A floor at y = 0 and a ceiling at y = 2; 100 pixels per metre and a 0.5 m margin.
  const LineMap map({{{0, 0}, {3, 0}}, {{0, 2}, {3, 2}}});
  const std::vector<std::vector<Eigen::Vector2d>> paths = {{{0.5, 0.5}, {2.5, 0.5}},
                                                           {{0.5, 1.5}, {2.5, 1.5}}};
  const TempDir dir;
  const std::filesystem::path path = dir / "map.svg";
  WriteSvg(map, path, paths, 100.0);
  const std::string svg = ReadAll(path);

  EXPECT_THAT(svg, HasSubstr("<svg"));
  EXPECT_THAT(svg, HasSubstr("</svg>"));
  EXPECT_EQ(Count(svg, "<line "), 2);
  EXPECT_EQ(Count(svg, "<polyline "), 2);
  EXPECT_THAT(svg, HasSubstr("width=\"400.000\" height=\"300.000\""));
  // The floor (y = 0) is drawn at the bottom: 2.5 m below the top edge.
  EXPECT_THAT(svg, HasSubstr("<line x1=\"50.000\" y1=\"250.000\" x2=\"350.000\" y2=\"250.000\""));
  EXPECT_THAT(svg, HasSubstr("<line x1=\"50.000\" y1=\"50.000\" x2=\"350.000\" y2=\"50.000\""));
  EXPECT_THAT(svg, HasSubstr("points=\"100.000,200.000 300.000,200.000\""));

  // Each polyline gets its own colour.
  const std::regex stroke("<polyline fill=\"none\" stroke=\"(#[0-9a-f]{6})\"");
  std::vector<std::string> colours;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), stroke); it != std::sregex_iterator();
       ++it) {
    colours.push_back((*it)[1]);
  }
  ASSERT_EQ(colours.size(), 2u);
  EXPECT_NE(colours[0], colours[1]);
}

TEST(LineMapSvgTest, PolylinesExtendTheDrawing) {
  const LineMap empty;
  const std::vector<std::vector<Eigen::Vector2d>> paths = {{{0, 0}, {4, 1}}};
  const TempDir dir;
  const std::filesystem::path path = dir / "path.svg";
  WriteSvg(empty, path, paths, 10.0);
  EXPECT_THAT(ReadAll(path), HasSubstr("width=\"50.000\" height=\"20.000\""));
}

TEST(LineMapSvgTest, UnwritablePathThrowsNamingIt) {
  const TempDir dir;
  const std::filesystem::path path = dir / "no_such_dir" / "map.svg";
  try {
    WriteSvg(LineMap(), path);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr(path.string()));
  }
}

}  // namespace
}  // namespace evoslam
