#include "common/image/marker.h"

#include <gtest/gtest.h>

#include <limits>

namespace evoslam {
namespace {

constexpr Rgb kMarkerInk{200, 20, 120};

TEST(MarkerTest, ADotFillsItsRadius) {
  Image image(41, 41);
  DrawMarker(image, 20, 20, Marker::kDot, 6.0, kMarkerInk);
  EXPECT_EQ(image.at(20, 20), kMarkerInk);
  EXPECT_EQ(image.at(26, 20), kMarkerInk);
  EXPECT_EQ(image.at(27, 20), kWhite);
}

TEST(MarkerTest, ARingLeavesItsMiddleAsItWas) {
  Image image(41, 41);
  DrawMarker(image, 20, 20, Marker::kRing, 8.0, kMarkerInk);
  EXPECT_EQ(image.at(20, 20), kWhite);
  EXPECT_EQ(image.at(24, 20), kWhite);
  for (const auto& [x, y] : {std::pair{28, 20}, std::pair{12, 20}, std::pair{20, 13}}) {
    EXPECT_EQ(image.at(x, y), kMarkerInk) << x << " " << y;
  }
  EXPECT_EQ(image.at(29, 20), kWhite);
  EXPECT_GT(CountPixels(image, kMarkerInk), 40) << "all the way round";
}

TEST(MarkerTest, ACrossIsDiagonalAndCentred) {
  Image image(41, 41);
  DrawMarker(image, 20, 20, Marker::kCross, 8.0, kMarkerInk);
  EXPECT_EQ(image.at(20, 20), kMarkerInk);
  for (const auto& [x, y] : {std::pair{24, 24}, std::pair{16, 16}, std::pair{24, 16}}) {
    EXPECT_EQ(image.at(x, y), kMarkerInk) << x << " " << y;
  }
  EXPECT_EQ(image.at(26, 20), kWhite) << "no upright arm";
  EXPECT_EQ(image.at(20, 26), kWhite) << "no upright arm";
  EXPECT_EQ(image.at(28, 28), kWhite) << "within the radius";
}

TEST(MarkerTest, MarkersClipAndIgnoreBadPlaces) {
  Image image(10, 10);
  for (const Marker m : {Marker::kDot, Marker::kRing, Marker::kCross}) {
    DrawMarker(image, -3, 5, m, 5.0, kMarkerInk);
    DrawMarker(image, std::numeric_limits<double>::quiet_NaN(), 5, m, 5.0, kMarkerInk);
    DrawMarker(image, 5, 1e300, m, 5.0, kMarkerInk);
    DrawMarker(image, 5, 5, m, -1.0, kMarkerInk);
  }
  EXPECT_GT(CountPixels(image, kMarkerInk), 0) << "the part inside";
  EXPECT_EQ(image.at(5, 5), kWhite);
}

}  // namespace
}  // namespace evoslam
