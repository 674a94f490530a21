#include "common/service/service_client.h"

#include <gtest/gtest.h>

namespace evoslam {
namespace {

TEST(MapYamlTest, FindsAndReplacesTheImagePath) {
  const std::string yaml = "resolution: 0.05\n  image:  \"maps/lab.pgm\" \norigin: [0, 0, 0]\n";
  EXPECT_EQ(MapYamlImage(yaml), "maps/lab.pgm");
  const std::string moved = WithMapYamlImage(yaml, "lab.pgm");
  EXPECT_EQ(MapYamlImage(moved), "lab.pgm");
  EXPECT_NE(moved.find("resolution: 0.05\n"), std::string::npos);
  EXPECT_NE(moved.find("origin: [0, 0, 0]\n"), std::string::npos);
  EXPECT_FALSE(MapYamlImage("resolution: 0.05\n"));
}

}  // namespace
}  // namespace evoslam
