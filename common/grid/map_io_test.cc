#include "common/grid/map_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "common/image/image.h"
#include "common/image/pgm.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class MapIoTest : public ::testing::Test {
 protected:
  fs::path WriteText(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  // A 3 x 2 plain PGM: top row 0 (occupied), 205 (unknown), 254 (free); bottom row 254, 100, 0.
  fs::path WriteSmallPgm(const std::string& name) {
    return WriteText(name, "P2\n3 2\n255\n0 205 254\n254 100 0\n");
  }

  static std::string Yaml(const std::string& image, const std::string& extra = "") {
    return "image: " + image +
           "\nresolution: 0.1\norigin: [1.5, -2.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\n"
           "free_thresh: 0.196\n" +
           extra;
  }

  // The InputError that reading `yaml` throws.
  InputError ReadError(const fs::path& yaml) {
    try {
      ReadMapYaml(yaml);
    } catch (const InputError& e) {
      return e;
    }
    ADD_FAILURE() << "no InputError for " << yaml;
    return InputError("", 0, "");
  }

  TempDir dir_;
};

TEST_F(MapIoTest, AnImageTooLargeForAGridIsRefusedOnItsHeaderNamingTheImage) {
  // The header alone: were the pixels read first, the fault would be the missing pixel data.
  WriteText("huge.pgm", "P5\n9000 9000\n255\n");
  const InputError e = ReadError(WriteText("huge.yaml", Yaml("huge.pgm")));
  EXPECT_EQ(fs::path(e.source()).filename(), "huge.pgm");
  EXPECT_THAT(e.message(), HasSubstr("9000 x 9000 pixels, more than the"));
}

TEST_F(MapIoTest, ReadsTrinaryPgmMap) {
  WriteSmallPgm("small.pgm");
  const OccupancyGrid grid = ReadMapYaml(WriteText("small.yaml", Yaml("small.pgm")));
  EXPECT_EQ(grid.width(), 3);
  EXPECT_EQ(grid.height(), 2);
  EXPECT_DOUBLE_EQ(grid.resolution(), 0.1);
  EXPECT_DOUBLE_EQ(grid.origin().x(), 1.5);
  EXPECT_DOUBLE_EQ(grid.origin().y(), -2.0);
  // PGM row 0 is the top of the map, grid row 1.
  EXPECT_EQ(grid.state(0, 1), CellState::kOccupied);
  EXPECT_EQ(grid.state(1, 1), CellState::kUnknown);
  EXPECT_EQ(grid.state(2, 1), CellState::kFree);
  EXPECT_EQ(grid.state(0, 0), CellState::kFree);
  EXPECT_EQ(grid.state(1, 0), CellState::kUnknown);  // p = 155/255 = 0.61
  EXPECT_EQ(grid.state(2, 0), CellState::kOccupied);
  EXPECT_TRUE(grid.has_distance_field());
  // Casting from the free cell (0, 0) to the right stops at the occupied cell (2, 0).
  EXPECT_NEAR(grid.CastRay(grid.CellToWorld(0, 0), 0.0, 5.0), 0.15, 1e-9);
}

TEST_F(MapIoTest, HonoursNegateThresholdsCommentsAndQuotes) {
  WriteSmallPgm("small.pgm");
  const fs::path yaml =
      WriteText("neg.yaml",
                "# a map\nimage: \"small.pgm\"  # quoted\nresolution: 0.1\norigin: [ 0, 0, 0 ]\n"
                "negate: 1\noccupied_thresh: 0.5\nfree_thresh: 0.3\nmode: trinary\nextra_key: 7\n");
  const OccupancyGrid grid = ReadMapYaml(yaml);
  // Negated: p = v / 255.
  EXPECT_EQ(grid.state(0, 1), CellState::kFree);      // 0
  EXPECT_EQ(grid.state(1, 1), CellState::kOccupied);  // 205 -> 0.80
  EXPECT_EQ(grid.state(2, 1), CellState::kOccupied);  // 254
  EXPECT_EQ(grid.state(1, 0), CellState::kUnknown);   // 100 -> 0.39
}

TEST_F(MapIoTest, ImagePathIsRelativeToYamlFolder) {
  WriteSmallPgm("maps/images/m.pgm");
  const OccupancyGrid grid = ReadMapYaml(WriteText("maps/m.yaml", Yaml("images/m.pgm")));
  EXPECT_EQ(grid.state(0, 1), CellState::kOccupied);
}

TEST_F(MapIoTest, ReadsPngImage) {
  Image image(2, 2);
  image.at(0, 0) = {0, 0, 0};
  image.at(1, 0) = {254, 254, 254};
  image.at(0, 1) = {205, 205, 205};
  image.at(1, 1) = {0, 0, 30};  // averages to 10: occupied
  WritePng(image, dir_ / "m.png");
  const OccupancyGrid grid = ReadMapYaml(WriteText("m.yaml", Yaml("m.png")));
  EXPECT_EQ(grid.state(0, 1), CellState::kOccupied);
  EXPECT_EQ(grid.state(1, 1), CellState::kFree);
  EXPECT_EQ(grid.state(0, 0), CellState::kUnknown);
  EXPECT_EQ(grid.state(1, 0), CellState::kOccupied);
}

TEST_F(MapIoTest, WriteReadRoundTrip) {
  std::mt19937 rng(5);
  OccupancyGrid grid(0.05, {-12.345678901, 3.25}, 37, 23);
  std::uniform_int_distribution<int> state(0, 2);
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) grid.SetCell(x, y, static_cast<CellState>(state(rng)));
  }
  const fs::path yaml = dir_ / "out" / "map.yaml";
  fs::create_directories(yaml.parent_path());
  WriteMapYaml(grid, yaml);
  ASSERT_TRUE(fs::exists(dir_ / "out" / "map.pgm"));
  const OccupancyGrid back = ReadMapYaml(yaml);
  ASSERT_EQ(back.width(), grid.width());
  ASSERT_EQ(back.height(), grid.height());
  EXPECT_EQ(back.resolution(), grid.resolution());
  EXPECT_EQ(back.origin(), grid.origin());
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      ASSERT_EQ(back.state(x, y), grid.state(x, y)) << x << "," << y;
    }
  }
  // The image uses map_server's values, top row first.
  const GrayImage pgm = ReadPgm(dir_ / "out" / "map.pgm");
  for (int x = 0; x < grid.width(); ++x) {
    const int expected = grid.state(x, grid.height() - 1) == CellState::kOccupied ? 0
                         : grid.state(x, grid.height() - 1) == CellState::kFree   ? 254
                                                                                  : 205;
    EXPECT_EQ(pgm.at(x, 0), expected);
  }
}

TEST_F(MapIoTest, WriteRejectsPgmYamlPathAndUnwritableFolder) {
  const OccupancyGrid grid(0.1, {0, 0}, 2, 2);
  EXPECT_THROW(WriteMapYaml(grid, dir_ / "map.pgm"), Error);
  EXPECT_THROW(WriteMapYaml(grid, dir_ / "missing" / "map.yaml"), Error);
}

TEST_F(MapIoTest, MissingKeysAreNamed) {
  WriteSmallPgm("small.pgm");
  const std::string keys[] = {"image",  "resolution",      "origin",
                              "negate", "occupied_thresh", "free_thresh"};
  const std::string full = Yaml("small.pgm");
  for (const std::string& key : keys) {
    std::string text;
    std::istringstream in(full);
    for (std::string line; std::getline(in, line);) {
      if (line.rfind(key + ":", 0) != 0) text += line + "\n";
    }
    const fs::path yaml = WriteText("missing_" + key + ".yaml", text);
    const InputError e = ReadError(yaml);
    EXPECT_EQ(e.source(), yaml.string());
    EXPECT_THAT(e.what(), HasSubstr("missing key '" + key + "'"));
  }
}

TEST_F(MapIoTest, BadValuesNameTheLine) {
  WriteSmallPgm("small.pgm");
  struct Case {
    std::string yaml;
    std::size_t line;
    std::string message;
  };
  const std::string img = "image: small.pgm\n";
  const std::string rest = "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  const Case cases[] = {
      {img + "resolution: fast\norigin: [0, 0, 0]\n" + rest, 2, "expected metres per pixel"},
      {img + "resolution: 0.05x\norigin: [0, 0, 0]\n" + rest, 2, "got '0.05x'"},
      {img + "resolution: -1\norigin: [0, 0, 0]\n" + rest, 2, "resolution must be positive"},
      {img + "resolution: 0.05\norigin: [0, 0]\n" + rest, 3, "3 numbers"},
      {img + "resolution: 0.05\norigin: 0, 0, 0\n" + rest, 3, "[x, y, yaw]"},
      {img + "resolution: 0.05\norigin: [0, a, 0]\n" + rest, 3, "origin coordinate"},
      {img + "resolution: 0.05\norigin: [0, 0, 0.5]\n" + rest, 3, "yaw"},
      {img + "resolution: 0.05\norigin: [0, 0, 0]\nnegate: 2\n" + rest.substr(10), 4,
       "negate 0 or 1"},
      {img + "resolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 1.5\n"
             "free_thresh: 0.196\n",
       5, "occupied_thresh"},
      {img + "resolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.5\n"
             "free_thresh: 0.7\n",
       6, "free_thresh"},
      {img + "resolution: 0.05\norigin: [0, 0, 0]\n" + rest + "mode: raw\n", 7, "mode 'raw'"},
      {img + "resolution 0.05\n", 2, "expected 'key: value'"},
      {img + "resolution: 0.05\n  nested: 1\n", 3, "nested"},
      {img + "resolution: 0.05\nimage: other.pgm\n", 3, "duplicate key 'image'"},
      {img + "resolution:\norigin: [0, 0, 0]\n" + rest, 2, "has no value"},
  };
  int n = 0;
  for (const Case& c : cases) {
    const fs::path yaml = WriteText("bad" + std::to_string(n++) + ".yaml", c.yaml);
    const InputError e = ReadError(yaml);
    EXPECT_EQ(e.source(), yaml.string()) << c.yaml;
    EXPECT_EQ(e.line(), c.line) << c.yaml;
    EXPECT_THAT(e.what(), HasSubstr(c.message)) << c.yaml;
  }
}

TEST_F(MapIoTest, MissingYamlOrImageFile) {
  EXPECT_THAT(ReadError(dir_ / "none.yaml").what(), HasSubstr("cannot open map YAML"));
  const fs::path yaml = WriteText("m.yaml", Yaml("absent.pgm"));
  const InputError e = ReadError(yaml);
  EXPECT_EQ(e.source(), yaml.string());
  EXPECT_EQ(e.line(), 1u);
  EXPECT_THAT(e.what(), HasSubstr("absent.pgm"));
}

TEST_F(MapIoTest, MalformedImagesNameTheImage) {
  const fs::path truncated = WriteText("t.pgm", "P5\n4 4\n255\n\x01\x02\x03");
  InputError e = ReadError(WriteText("t.yaml", Yaml("t.pgm")));
  EXPECT_EQ(e.source(), truncated.string());
  EXPECT_THAT(e.what(), HasSubstr("truncated"));

  const fs::path wrong = WriteText("w.pgm", "P2\n2 2\n255\n1 2 3 4 5 6\n");
  e = ReadError(WriteText("w.yaml", Yaml("w.pgm")));
  EXPECT_EQ(e.source(), wrong.string());
  EXPECT_THAT(e.what(), HasSubstr("size looks wrong"));

  const fs::path text = WriteText("x.pgm", "hello");
  e = ReadError(WriteText("x.yaml", Yaml("x.pgm")));
  EXPECT_EQ(e.source(), text.string());
  EXPECT_THAT(e.what(), HasSubstr("expected a PGM or PNG file"));
}

}  // namespace
}  // namespace evoslam
