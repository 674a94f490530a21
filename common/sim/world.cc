#include "common/sim/world.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <utility>

#include "common/line_map/segment_geometry.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

using Points = std::vector<Eigen::Vector2d>;

// Scan spacings of the experiments: logged scans over route length.
constexpr double kOfficeBoxesSpacing = 30.0111 / 350;     // 350 scans over 3001.11 cm
constexpr double kSCorridorSpacing = 11.564 / 219;        // 219 scans over 1156.4 cm
constexpr double kStaticObjectsSpacing = 30.0 / 350;      // 350 scans over about 30 m
constexpr double kOfficeClusterSpacing = 236.296 / 1832;  // 1832 scans over 23629.6 cm

void AddPolygon(std::vector<Segment>* walls, const Points& corners) {
  for (std::size_t i = 0; i < corners.size(); ++i) {
    walls->push_back({corners[i], corners[(i + 1) % corners.size()]});
  }
}

// A rectangular object of the given size, centred at c, turned by angle_deg.
void AddBox(std::vector<Segment>* walls, Eigen::Vector2d c, double width, double height,
            double angle_deg = 0.0) {
  const double a = angle_deg * std::numbers::pi / 180.0;
  const Eigen::Vector2d u = 0.5 * width * Eigen::Vector2d(std::cos(a), std::sin(a));
  const Eigen::Vector2d v = 0.5 * height * Eigen::Vector2d(-std::sin(a), std::cos(a));
  AddPolygon(walls, {c - u - v, c + u - v, c + u + v, c - u + v});
}

// 10 x 10 m with fourteen 40 x 60 cm boxes: seven against the walls and seven inside the loop
// the robot drives.
World OfficeBoxes() {
  std::vector<Segment> walls;
  AddPolygon(&walls, {{0, 0}, {10, 0}, {10, 10}, {0, 10}});
  const struct {
    double x, y, w, h;
  } boxes[] = {
      {3.0, 0.3, 0.6, 0.4}, {6.5, 0.3, 0.6, 0.4}, {9.7, 3.0, 0.4, 0.6}, {9.7, 6.5, 0.4, 0.6},
      {7.0, 9.7, 0.6, 0.4}, {3.5, 9.7, 0.6, 0.4}, {0.3, 6.0, 0.4, 0.6}, {3.0, 5.5, 0.6, 0.4},
      {5.0, 6.5, 0.4, 0.6}, {6.5, 5.0, 0.6, 0.4}, {7.2, 7.2, 0.4, 0.6}, {3.5, 7.3, 0.6, 0.4},
      {6.0, 2.6, 0.6, 0.4}, {5.4, 4.0, 0.4, 0.6},
  };
  for (const auto& b : boxes) AddBox(&walls, {b.x, b.y}, b.w, b.h);
  return {"office-boxes",
          LineMap(std::move(walls)),
          {{1.2, 1.2}, {8.8, 1.2}, {8.8, 8.8}, {1.2, 8.8}, {1.2, 3.5}, {4.2, 3.5}},
          kOfficeBoxesSpacing};
}

// A 1.8 m wide corridor folded into an S: bottom leg east, up on the right, middle leg west, up
// on the left, top leg east. A few odd-angled boxes stand in its dead ends and a corner.
World SCorridor() {
  std::vector<Segment> walls;
  AddPolygon(&walls, {{0, 0},
                      {6, 0},
                      {6, 4.8},
                      {1.8, 4.8},
                      {1.8, 6.0},
                      {6, 6.0},
                      {6, 7.8},
                      {0, 7.8},
                      {0, 3.0},
                      {4.2, 3.0},
                      {4.2, 1.8},
                      {0, 1.8}});
  AddBox(&walls, {1.2, 0.9}, 0.5, 0.4, 30.0);
  AddBox(&walls, {5.75, 0.25}, 0.3, 0.3, 10.0);
  AddBox(&walls, {4.5, 6.9}, 0.6, 0.4, -20.0);
  return {"s-corridor",
          LineMap(std::move(walls)),
          {{3.5, 0.9}, {5.1, 0.9}, {5.1, 3.9}, {0.9, 3.9}, {0.9, 6.9}, {1.5, 6.9}},
          kSCorridorSpacing};
}

// 8 x 6.2 m with fourteen boxes, some turned, between the three east-west lanes of the route
// and along the walls.
World StaticObjects() {
  std::vector<Segment> walls;
  AddPolygon(&walls, {{0, 0}, {8, 0}, {8, 6.2}, {0, 6.2}});
  const struct {
    double x, y, w, h, angle;
  } boxes[] = {
      {1.0, 2.1, 0.6, 0.4, 0},  {2.8, 2.1, 0.6, 0.4, 20},  {4.4, 2.1, 0.6, 0.4, -15},
      {5.8, 2.1, 0.6, 0.4, 0},  {2.3, 4.1, 0.6, 0.4, -20}, {3.9, 4.1, 0.4, 0.6, 0},
      {5.6, 4.1, 0.6, 0.4, 15}, {2.5, 0.3, 0.6, 0.4, 0},   {5.0, 0.3, 0.6, 0.4, 0},
      {1.9, 5.9, 0.6, 0.4, 0},  {4.6, 5.9, 0.6, 0.4, 0},   {0.3, 4.1, 0.4, 0.6, 0},
      {7.7, 2.1, 0.4, 0.6, 0},  {7.7, 4.3, 0.4, 0.6, 0},
  };
  for (const auto& b : boxes) AddBox(&walls, {b.x, b.y}, b.w, b.h, b.angle);
  return {"static-objects",
          LineMap(std::move(walls)),
          {{1.1, 1.1},
           {6.9, 1.1},
           {6.9, 5.1},
           {1.1, 5.1},
           {1.1, 3.1},
           {6.9, 3.1},
           {6.9, 1.1},
           {1.8, 1.1}},
          kStaticObjectsSpacing};
}

World EmptyRoom() {
  std::vector<Segment> walls;
  AddPolygon(&walls, {{0, 0}, {8, 0}, {8, 6}, {0, 6}});
  return {"empty-room",
          LineMap(std::move(walls)),
          {{1, 1}, {7, 1}, {7, 5}, {1, 5}, {1, 2}, {5, 3}},
          kStaticObjectsSpacing};
}

// Ten 5.12 x 8.4 m offices, five on each side of a 2 m hallway, each entered by a 1.3 m door
// in the middle of its hallway wall and furnished with seven or eight of ten pieces (cabinets,
// shelves, desks), 328 walls in all. Layouts are given in office coordinates: u across the office,
// v from the hallway wall inwards.
World OfficeCluster() {
  constexpr double kWidth = 25.6;
  constexpr double kHeight = 18.8;
  constexpr double kHallLow = 8.4;  // hallway between y = 8.4 and y = 10.4
  constexpr double kHallHigh = 10.4;
  constexpr double kHallMid = 0.5 * (kHallLow + kHallHigh);
  constexpr int kOfficesPerSide = 5;
  constexpr double kOfficeWidth = kWidth / kOfficesPerSide;
  constexpr double kDoorHalf = 0.65;

  std::vector<Segment> walls;
  AddPolygon(&walls, {{0, 0}, {kWidth, 0}, {kWidth, kHeight}, {0, kHeight}});
  for (const double y : {kHallLow, kHallHigh}) {
    double x = 0.0;
    for (int k = 0; k < kOfficesPerSide; ++k) {
      const double door = (k + 0.5) * kOfficeWidth;
      walls.push_back({{x, y}, {door - kDoorHalf, y}});
      x = door + kDoorHalf;
    }
    walls.push_back({{x, y}, {kWidth, y}});
  }
  for (int k = 1; k < kOfficesPerSide; ++k) {
    walls.push_back({{k * kOfficeWidth, 0}, {k * kOfficeWidth, kHallLow}});
    walls.push_back({{k * kOfficeWidth, kHallHigh}, {k * kOfficeWidth, kHeight}});
  }

  const struct {
    double u, v, w, h;
  } furniture[] = {
      {0.3, 2.4, 0.4, 0.8},  {0.3, 4.6, 0.4, 1.2},  {0.3, 7.4, 0.4, 0.6},  {4.82, 2.6, 0.4, 0.8},
      {4.82, 5.2, 0.4, 1.2}, {2.56, 8.0, 1.6, 0.6}, {2.55, 3.2, 1.2, 0.6}, {2.55, 5.0, 1.2, 0.6},
      {4.2, 0.45, 0.6, 0.4}, {0.7, 0.45, 0.6, 0.4},
  };
  constexpr int kPieces = sizeof(furniture) / sizeof(furniture[0]);

  // Offices 0..4 south of the hallway (v grows southwards), 5..9 north of it.
  const auto to_world = [&](int office, double u, double v) -> Eigen::Vector2d {
    const double x0 = (office % kOfficesPerSide) * kOfficeWidth;
    return office < kOfficesPerSide ? Eigen::Vector2d(x0 + u, kHallLow - v)
                                    : Eigen::Vector2d(x0 + u, kHallHigh + v);
  };
  for (int office = 0; office < 2 * kOfficesPerSide; ++office) {
    // Each office leaves out two pieces, and four of them a third, so that no two look alike.
    const int skip1 = (3 * office) % kPieces;
    const int skip2 = (3 * office + 5) % kPieces;
    const int skip3 = office < 4 ? (3 * office + 7) % kPieces : -1;
    // Desks move along v a little from office to office.
    const double desk_shift = 0.1 * ((office * 7) % 5 - 2);
    for (int p = 0; p < kPieces; ++p) {
      if (p == skip1 || p == skip2 || p == skip3) continue;
      const auto& f = furniture[p];
      const double v = f.v + (p == 6 || p == 7 ? desk_shift : 0.0);
      const Eigen::Vector2d c = to_world(office, f.u, v);
      AddBox(&walls, c, f.w, f.h);
    }
  }

  // Along the hallway eastwards; at each door, a loop through the southern office and then
  // straight across into the northern one; finally back west along the hallway.
  const Points loop = {{2.56, 1.5}, {1.2, 1.5}, {1.2, 6.6}, {3.9, 6.6}, {3.9, 1.5}, {2.56, 1.5}};
  Points route = {{1.0, kHallMid}};
  for (int k = 0; k < kOfficesPerSide; ++k) {
    const double door = (k + 0.5) * kOfficeWidth;
    route.emplace_back(door, kHallMid);
    for (const int office : {k, k + kOfficesPerSide}) {
      for (const Eigen::Vector2d& p : loop) route.push_back(to_world(office, p.x(), p.y()));
    }
    route.emplace_back(door, kHallMid);
  }
  route.emplace_back(1.0, kHallMid);
  return {"office-cluster", LineMap(std::move(walls)), std::move(route), kOfficeClusterSpacing};
}

// A loop through the free space of any map: the outline of the largest region of lattice points
// that keep clear of the walls (and is enclosed by them), simplified to fewer legs.
Points AutoRoute(const LineMap& map) {
  constexpr double kNodeClearance = 0.6;
  constexpr double kLegClearance = kMinWallClearance;
  constexpr double kSimplifyTolerance = 0.2;
  constexpr double kMaxNodes = 4e6;
  const Eigen::Vector2d extent = map.bounds().max - map.bounds().min;
  double spacing = 0.1;
  while ((extent.x() / spacing + 2) * (extent.y() / spacing + 2) > kMaxNodes) spacing *= 1.5;
  const int cols = static_cast<int>(std::ceil(extent.x() / spacing)) + 1;
  const int rows = static_cast<int>(std::ceil(extent.y() / spacing)) + 1;
  const auto position = [&](int node) {
    return Eigen::Vector2d(map.bounds().min + spacing * Eigen::Vector2d(node % cols, node / cols));
  };
  const int nodes = cols * rows;
  std::vector<char> free(nodes, 0);
  for (int n = 0; n < nodes; ++n) free[n] = map.SegmentsNear(position(n), kNodeClearance).empty();

  // Neighbours counter-clockwise from east.
  constexpr int kDx[8] = {1, 1, 0, -1, -1, -1, 0, 1};
  constexpr int kDy[8] = {0, 1, 1, 1, 0, -1, -1, -1};
  const auto neighbour = [&](int node, int k) {
    const int c = node % cols + kDx[k];
    const int r = node / cols + kDy[k];
    return c < 0 || r < 0 || c >= cols || r >= rows ? -1 : r * cols + c;
  };

  // Regions of 8-connected free points. A region reaching the lattice's border lies outside the
  // walls (inside, the outer walls would be within the clearance), so it is not a candidate.
  std::vector<int> region(nodes, -1);
  int best = -1;
  std::size_t best_size = 0;
  for (int root = 0; root < nodes; ++root) {
    if (!free[root] || region[root] >= 0) continue;
    std::vector<int> queue = {root};
    region[root] = root;
    bool outside = false;
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const int node = queue[q];
      const int c = node % cols;
      const int r = node / cols;
      outside = outside || c == 0 || r == 0 || c == cols - 1 || r == rows - 1;
      for (int k = 0; k < 8; ++k) {
        const int j = neighbour(node, k);
        if (j >= 0 && free[j] && region[j] < 0) {
          region[j] = root;
          queue.push_back(j);
        }
      }
    }
    if (!outside && queue.size() > best_size) {
      best = root;
      best_size = queue.size();
    }
  }
  if (best_size < 2) {
    throw Error(
        "no room for a route: no enclosed free area keeps 0.6 m from the walls (give waypoints)");
  }

  // Moore-neighbour tracing of the region's outline, from its first point in raster order
  // (whose west neighbour is outside), until it would leave that point the same way again.
  const auto inside = [&](int node) { return node >= 0 && region[node] == best; };
  std::vector<int> outline = {best};
  int current = best;
  int back = 4;  // direction of the last outside neighbour looked at: west
  for (std::size_t guard = 0; guard < 8 * best_size + 8; ++guard) {
    int next = -1;
    int k = back;
    for (int turn = 1; turn <= 8; ++turn) {
      const int candidate = (back + 8 - turn) % 8;  // clockwise from back
      if (inside(neighbour(current, candidate))) {
        next = candidate;
        break;
      }
      k = candidate;
    }
    if (next < 0) break;  // a lone point
    const int moved = neighbour(current, next);
    // The outside neighbour looked at last, seen from the new point.
    const int dx = (current % cols + kDx[k]) - moved % cols;
    const int dy = (current / cols + kDy[k]) - moved / cols;
    for (int d = 0; d < 8; ++d) {
      if (kDx[d] == dx && kDy[d] == dy) back = d;
    }
    if (current == best && outline.size() > 1 && moved == outline[1]) break;
    current = moved;
    outline.push_back(current);
  }

  Points loop;
  for (const int node : outline) loop.push_back(position(node));
  // Replace runs of outline points by one straight leg where the leg stays clear of the walls
  // and passes near every point it replaces.
  const auto can_replace = [&](std::size_t i, std::size_t k) {
    const Segment leg{loop[i], loop[k]};
    for (std::size_t m = i + 1; m < k; ++m) {
      if (PointSegmentDistance(loop[m], leg) > kSimplifyTolerance) return false;
    }
    return WallClearance(map, leg, kLegClearance) >= kLegClearance;
  };
  Points route = {loop.front()};
  std::size_t i = 0;
  while (i + 1 < loop.size()) {
    std::size_t k = i + 1;
    while (k + 1 < loop.size() && can_replace(i, k + 1)) ++k;
    route.push_back(loop[k]);
    i = k;
  }
  return route;
}

}  // namespace

std::vector<std::string> BuiltinWorldNames() {
  return {"office-boxes", "s-corridor", "static-objects", "empty-room", "office-cluster"};
}

World BuiltinWorld(std::string_view name) {
  if (name == "office-boxes") return OfficeBoxes();
  if (name == "s-corridor") return SCorridor();
  if (name == "static-objects") return StaticObjects();
  if (name == "empty-room") return EmptyRoom();
  if (name == "office-cluster") return OfficeCluster();
  std::string known;
  for (const std::string& n : BuiltinWorldNames()) known += (known.empty() ? "" : ", ") + n;
  throw Error("unknown world \"" + std::string(name) + "\"; built-in worlds: " + known);
}

World WorldFromLineMap(LineMap map, std::string name, std::vector<Eigen::Vector2d> waypoints) {
  if (map.empty()) throw Error("world \"" + name + "\": the line map has no walls");
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    if (!waypoints[i].allFinite()) {
      throw Error("world \"" + name + "\": waypoint " + std::to_string(i) + " is not finite");
    }
  }
  if (waypoints.empty()) {
    try {
      waypoints = AutoRoute(map);
    } catch (const Error& e) {
      throw Error("world \"" + name + "\": " + e.what());
    }
  }
  return {std::move(name), std::move(map), std::move(waypoints), kDefaultScanSpacing};
}

}  // namespace evoslam
