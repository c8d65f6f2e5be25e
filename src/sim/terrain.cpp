#include "sim/terrain.hpp"

#include <fmt/format.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/math.hpp"

namespace mimic {

const char* to_string(TerrainKind kind) {
  switch (kind) {
    case TerrainKind::Flat: return "flat";
    case TerrainKind::Slope: return "slope";
    case TerrainKind::Gaps: return "gaps";
    case TerrainKind::Stairs: return "stairs";
    case TerrainKind::HeightField: return "heightfield";
    case TerrainKind::Walls: return "walls";
  }
  return "?";
}

TerrainKind terrain_kind_from_string(const std::string& name) {
  for (TerrainKind k : {TerrainKind::Flat, TerrainKind::Slope, TerrainKind::Gaps, TerrainKind::Stairs, TerrainKind::HeightField, TerrainKind::Walls})
    if (name == to_string(k)) return k;
  throw Error("terrain: unknown kind '" + name + "' (known: flat, slope, gaps, stairs, heightfield, walls)");
}

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw Error("terrain: " + what);
}

// A uniform number in [0, 1) from (seed, i, j): splitmix64, the same on every platform and
// standard library (std distributions are not).
double hash01(std::uint64_t seed, std::int64_t i, std::int64_t j) {
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(i) * 0xBF58476D1CE4E5B9ull +
                    static_cast<std::uint64_t>(j) * 0x94D049BB133111EBull;
  for (int k = 0; k < 2; ++k) {
    z += 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
  }
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

// Value noise in [0, 1]: lattice values blended with smoothstep (smooth bumps of lattice size).
double value_noise(std::uint64_t seed, double u, double v) {
  const double fu = std::floor(u), fv = std::floor(v);
  const auto i = static_cast<std::int64_t>(fu), j = static_cast<std::int64_t>(fv);
  auto s = [](double t) { return t * t * (3 - 2 * t); };
  const double a = s(u - fu), b = s(v - fv);
  const double top = (1 - a) * hash01(seed, i, j) + a * hash01(seed, i + 1, j);
  const double bottom = (1 - a) * hash01(seed, i, j + 1) + a * hash01(seed, i + 1, j + 1);
  return (1 - b) * top + b * bottom;
}

std::string num(double v) { return fmt::format("{:.9g}", v); }

constexpr double kWallMargin = 0.05;  // m: the least of a wall on each side of its opening

}  // namespace

Terrain::Terrain(const TerrainSpec& spec) : spec_(spec), top_(spec) {
  const TerrainSpec& s = spec_;
  require(s.start_zone >= 0 && s.behind > 0 && s.ahead > s.start_zone && s.width > 0,
          "need start_zone >= 0, behind > 0, ahead > start_zone and width > 0");
  require(!s.redraw || s.kind == TerrainKind::Walls, std::string("redraw: only a walls course is redrawn, not '") + to_string(s.kind) + "'");
  require(s.levels >= 0 && s.levels <= 1000, "levels: need 0 (no curriculum) to 1000");
  require(s.levels == 0 || (s.kind != TerrainKind::Flat && s.kind != TerrainKind::Walls),
          std::string("levels: a curriculum scales stairs, gaps, slope or heightfield, not '") + to_string(s.kind) + "'");
  level_ = s.levels;
  build();
}

void Terrain::build() {
  switch (spec_.kind) {
    case TerrainKind::Flat: break;
    case TerrainKind::Slope: build_slope(); break;
    case TerrainKind::Gaps: build_gaps(); break;
    case TerrainKind::Stairs: build_stairs(); break;
    case TerrainKind::HeightField: build_heightfield(); break;
    case TerrainKind::Walls: build_walls(); break;
  }
}

double Terrain::course_end() const {
  const TerrainSpec& s = spec_;
  switch (s.kind) {
    case TerrainKind::Flat: break;
    case TerrainKind::Slope: return s.start_zone + s.slope_segments * s.slope_length;
    case TerrainKind::Gaps: return s.start_zone + s.gap_count * s.gap_width + (s.gap_count - 1) * s.gap_spacing;
    case TerrainKind::Stairs: return s.start_zone + (2 * s.step_count - 1) * s.step_depth + s.landing;
    case TerrainKind::HeightField: return s.ahead;
    case TerrainKind::Walls: return s.start_zone + (s.wall_count - 1) * s.wall_spacing + s.wall_thickness;
  }
  throw Error("terrain: flat ground has no course to cross");
}

void Terrain::build_slope() {
  const TerrainSpec& s = spec_;
  require(std::abs(s.slope_deg) < 60 && s.slope_length > 0 && s.slope_segments >= 1, "slope: need |slope_deg| < 60, slope_length > 0, slope_segments >= 1");
  require(s.start_zone + s.slope_segments * s.slope_length <= s.ahead, "slope: the inclines run past 'ahead'");
  require(s.resolution > 0, "slope: resolution must be positive");
  std::vector<double> tans;
  for (int k = 0; k < s.slope_segments; ++k) {
    const double deg = s.slope_segments == 1 ? s.slope_deg : (2 * hash01(s.seed, k, -1) - 1) * s.slope_deg;
    tans.push_back(std::tan(deg_to_rad(deg)));
  }
  // Piecewise-linear profile along x; constant along y, so two rows suffice.
  auto profile = [&](double x) {
    double h = 0, at = s.start_zone;
    for (double t : tans) {
      h += t * std::clamp(x - at, 0.0, s.slope_length);
      at += s.slope_length;
    }
    return h;
  };
  Grid& g = grid_;
  g.ncol = static_cast<int>(std::lround((s.ahead + s.behind) / s.resolution)) + 1;
  g.nrow = 2;
  g.x0 = -s.behind, g.y0 = -s.width / 2;
  g.dx = (s.ahead + s.behind) / (g.ncol - 1), g.dy = s.width;
  for (int r = 0; r < g.nrow; ++r)
    for (int c = 0; c < g.ncol; ++c) g.z.push_back(profile(g.x0 + c * g.dx));
  finish_grid();
  base_ = g.lo;  // ground beyond the terrain: the lowest point of the slope or 0
}

void Terrain::build_gaps() {
  const TerrainSpec& s = spec_;
  require(s.gap_width > 0 && s.gap_spacing > 0 && s.gap_depth > 0 && s.gap_count >= 1, "gaps: need positive gap_width, gap_spacing, gap_depth and gap_count");
  require(s.start_zone + s.gap_count * (s.gap_width + s.gap_spacing) <= s.ahead, "gaps: the gaps run past 'ahead'");
  base_ = -s.gap_depth;  // the gaps' floor
  const double y0 = -s.width / 2, y1 = s.width / 2;
  double x = s.start_zone;
  boxes_.push_back(Box{-s.behind, x, y0, y1, 0.0});
  for (int k = 0; k < s.gap_count; ++k) {
    x += s.gap_width;
    const double end = k + 1 == s.gap_count ? s.ahead : x + s.gap_spacing;
    boxes_.push_back(Box{x, end, y0, y1, 0.0});
    x = end;
  }
}

void Terrain::build_stairs() {
  const TerrainSpec& s = spec_;
  require(s.step_height > 0 && s.step_depth > 0 && s.step_count >= 1 && s.landing >= 0, "stairs: need positive step_height, step_depth, step_count and landing >= 0");
  const double up_end = s.start_zone + s.step_count * s.step_depth;
  require(up_end + s.landing + (s.step_count - 1) * s.step_depth <= s.ahead, "stairs: the stairs run past 'ahead'");
  const double y0 = -s.width / 2, y1 = s.width / 2;
  // Up, the landing (part of the last step up), then down to the ground.
  for (int k = 0; k < s.step_count; ++k) {
    const double x = s.start_zone + k * s.step_depth;
    boxes_.push_back(Box{x, k + 1 == s.step_count ? up_end + s.landing : x + s.step_depth, y0, y1, (k + 1) * s.step_height});
  }
  for (int k = 1; k < s.step_count; ++k) {
    const double x = up_end + s.landing + (k - 1) * s.step_depth;
    boxes_.push_back(Box{x, x + s.step_depth, y0, y1, (s.step_count - k) * s.step_height});
  }
}

void Terrain::build_walls() {
  const TerrainSpec& s = spec_;
  require(s.wall_count >= 1 && s.wall_spacing > 0 && s.wall_height > 0 && s.wall_thickness > 0 && s.opening_width > 0,
          "walls: need positive wall_count, wall_spacing, wall_height, wall_thickness and opening_width");
  require(s.opening_width < s.width, "walls: the opening must be narrower than the course's width");
  require(s.wall_spacing > s.wall_thickness, "walls: wall_spacing must exceed wall_thickness");
  require(s.start_zone + (s.wall_count - 1) * s.wall_spacing + s.wall_thickness <= s.ahead, "walls: the walls run past 'ahead'");
  require(s.opening_width + 2 * kWallMargin < s.width, "walls: the opening must leave 5 cm of wall on each side");
  const double y0 = -s.width / 2, y1 = s.width / 2, half = s.opening_width / 2;
  // Two parts a wall, each at least kWallMargin wide, so that every seed's course has the same boxes.
  for (int k = 0; k < s.wall_count; ++k) {
    const double x = s.start_zone + k * s.wall_spacing;
    const double centre = y0 + kWallMargin + half + hash01(s.seed, k, 1) * (s.width - s.opening_width - 2 * kWallMargin);
    boxes_.push_back(Box{x, x + s.wall_thickness, y0, centre - half, s.wall_height});
    boxes_.push_back(Box{x, x + s.wall_thickness, centre + half, y1, s.wall_height});
  }
}

void Terrain::redraw(std::uint64_t seed, mjModel_* m) {
  if (spec_.kind != TerrainKind::Walls) throw Error(std::string("terrain: only walls are redrawn, not '") + to_string(spec_.kind) + "'");
  spec_.seed = seed;
  boxes_.clear();
  build_walls();
  move_boxes(m);
}

void Terrain::set_level(int level, mjModel_* m) {
  if (top_.levels == 0) throw Error("terrain: set_level on a course without a curriculum (levels: 0)");
  require(level >= 1 && level <= top_.levels, fmt::format("level {} is outside 1..{}", level, top_.levels));
  const double f = static_cast<double>(level) / top_.levels;
  spec_ = top_;
  switch (spec_.kind) {
    case TerrainKind::Stairs: spec_.step_height *= f; break;
    case TerrainKind::Gaps: spec_.gap_width *= f; break;
    case TerrainKind::Slope: spec_.slope_deg *= f; break;
    case TerrainKind::HeightField: spec_.roughness *= f; break;
    case TerrainKind::Flat:
    case TerrainKind::Walls: break;  // refused by the constructor
  }
  boxes_.clear();
  grid_ = Grid{};
  build();
  level_ = level;
  if (!boxes_.empty()) move_boxes(m);
  if (grid_.z.empty()) return;
  // The height field: its samples, its vertical extent and where it and the plane beyond stand.
  const int h = mj_name2id(m, mjOBJ_HFIELD, "terrain"), g = mj_name2id(m, mjOBJ_GEOM, "terrain_hfield");
  const int plane = mj_name2id(m, mjOBJ_GEOM, "terrain_base");
  if (h < 0 || g < 0 || plane < 0) throw Error("terrain: the model has no height field geom (build it with Terrain::add_to)");
  m->hfield_size[4 * h + 2] = std::max(grid_.hi - grid_.lo, 1e-6);
  m->geom_pos[3 * g + 2] = grid_.lo;
  m->geom_pos[3 * plane + 2] = base_;
  install(m);
}

void Terrain::move_boxes(mjModel_* m) const {
  for (std::size_t k = 0; k < boxes_.size(); ++k) {
    const int g = mj_name2id(m, mjOBJ_GEOM, fmt::format("terrain_box{}", k).c_str());
    if (g < 0) throw Error("terrain: the model has no geom terrain_box" + std::to_string(k) + " (build it with Terrain::add_to)");
    const Box& b = boxes_[k];
    const double size[3] = {(b.x1 - b.x0) / 2, (b.y1 - b.y0) / 2, (b.top - base_) / 2};
    const double pos[3] = {(b.x0 + b.x1) / 2, (b.y0 + b.y1) / 2, (b.top + base_) / 2};
    for (int i = 0; i < 3; ++i) m->geom_size[3 * g + i] = size[i], m->geom_pos[3 * g + i] = pos[i];
    m->geom_rbound[g] = std::sqrt(size[0] * size[0] + size[1] * size[1] + size[2] * size[2]);  // the broad phase's sphere
  }
}

void Terrain::build_heightfield() {
  const TerrainSpec& s = spec_;
  require(s.roughness > 0 && s.feature > 0 && s.resolution > 0, "heightfield: need positive roughness, feature and resolution");
  Grid& g = grid_;
  g.ncol = static_cast<int>(std::lround((s.ahead + s.behind) / s.resolution)) + 1;
  g.nrow = static_cast<int>(std::lround(s.width / s.resolution)) + 1;
  require(static_cast<double>(g.ncol) * g.nrow <= 4e6, "heightfield: more than 4 million samples; raise the resolution");
  g.x0 = -s.behind, g.y0 = -s.width / 2;
  g.dx = (s.ahead + s.behind) / (g.ncol - 1), g.dy = s.width / (g.nrow - 1);
  const double blend = std::max(s.feature, s.resolution);  // bumps grow over this distance past the start zone
  for (int r = 0; r < g.nrow; ++r) {
    for (int c = 0; c < g.ncol; ++c) {
      const double x = g.x0 + c * g.dx, y = g.y0 + r * g.dy;
      const double w = std::clamp((std::max(std::abs(x), std::abs(y)) - s.start_zone) / blend, 0.0, 1.0);
      g.z.push_back(w * s.roughness * value_noise(s.seed, x / s.feature, y / s.feature));
    }
  }
  finish_grid();
}

void Terrain::finish_grid() {
  // MuJoCo keeps height-field samples as floats: round them here too, so height() is exact.
  Grid& g = grid_;
  const auto [lo, hi] = std::minmax_element(g.z.begin(), g.z.end());
  g.lo = *lo, g.hi = *hi;
  const double range = std::max(g.hi - g.lo, 1e-6);
  for (double& z : g.z) z = g.lo + static_cast<double>(static_cast<float>((z - g.lo) / range)) * range;
}

double Terrain::grid_height(double x, double y) const {
  // MuJoCo's height-field surface: each cell split along the diagonal (r, c)-(r+1, c+1).
  const Grid& g = grid_;
  const double u = std::clamp((x - g.x0) / g.dx, 0.0, g.ncol - 1.0), v = std::clamp((y - g.y0) / g.dy, 0.0, g.nrow - 1.0);
  const int c = std::min(static_cast<int>(u), g.ncol - 2), r = std::min(static_cast<int>(v), g.nrow - 2);
  const double a = u - c, b = v - r;
  const double z00 = g.at(r, c), z11 = g.at(r + 1, c + 1);
  if (a >= b) return z00 + a * (g.at(r, c + 1) - z00) + b * (z11 - g.at(r, c + 1));
  return z00 + b * (g.at(r + 1, c) - z00) + a * (z11 - g.at(r + 1, c));
}

double Terrain::height(double x, double y) const {
  const TerrainSpec& s = spec_;
  if (s.kind == TerrainKind::Flat) return 0.0;
  if (x < -s.behind || x > s.ahead || std::abs(y) > s.width / 2) return base_;
  if (!grid_.z.empty()) return grid_height(x, y);
  double h = base_;
  for (const Box& b : boxes_)
    if (x >= b.x0 && x <= b.x1 && y >= b.y0 && y <= b.y1) h = std::max(h, b.top);
  return h;
}

void Terrain::add_to(MjcfOptions& opts) const {
  if (spec_.kind == TerrainKind::Flat) return;
  opts.floor = false;
  std::string& w = opts.extra_worldbody;
  const char* ground = "contype=\"1\" conaffinity=\"1\" material=\"grid\"";
  w += fmt::format("    <geom name=\"terrain_base\" type=\"plane\" pos=\"0 0 {}\" size=\"100 100 0.1\" {}/>\n", num(base_), ground);
  for (std::size_t k = 0; k < boxes_.size(); ++k) {
    const Box& b = boxes_[k];
    w += fmt::format("    <geom name=\"terrain_box{}\" type=\"box\" pos=\"{} {} {}\" size=\"{} {} {}\" {}/>\n", k, num((b.x0 + b.x1) / 2),
                     num((b.y0 + b.y1) / 2), num((b.top + base_) / 2), num((b.x1 - b.x0) / 2), num((b.y1 - b.y0) / 2), num((b.top - base_) / 2), ground);
  }
  if (grid_.z.empty()) return;
  // MuJoCo 2.2 takes no elevation data in MJCF: a zero grid here, filled in by install().
  const Grid& g = grid_;
  const double hx = g.dx * (g.ncol - 1) / 2, hy = g.dy * (g.nrow - 1) / 2;
  opts.extra_assets += fmt::format("    <hfield name=\"terrain\" nrow=\"{}\" ncol=\"{}\" size=\"{} {} {} {}\"/>\n", g.nrow, g.ncol, num(hx),
                                   num(hy), num(std::max(g.hi - g.lo, 1e-6)), num(1.0));
  w += fmt::format("    <geom name=\"terrain_hfield\" type=\"hfield\" hfield=\"terrain\" pos=\"{} {} {}\" {}/>\n", num(g.x0 + hx), num(g.y0 + hy),
                   num(g.lo), ground);
}

void Terrain::install(mjModel_* m) const {
  if (grid_.z.empty()) return;
  const int h = mj_name2id(m, mjOBJ_HFIELD, "terrain");
  const Grid& g = grid_;
  if (h < 0 || m->hfield_nrow[h] != g.nrow || m->hfield_ncol[h] != g.ncol)
    throw Error(std::string("terrain: the model has no matching height field for the '") + to_string(spec_.kind) + "' terrain (build it with Terrain::add_to)");
  // Row r at y0 + r * dy, as MuJoCo's collisions and rays read it; values in [0, 1] of size[2].
  const double range = std::max(g.hi - g.lo, 1e-6);
  float* data = m->hfield_data + m->hfield_adr[h];
  for (std::size_t i = 0; i < g.z.size(); ++i) data[i] = static_cast<float>((g.z[i] - g.lo) / range);
}

}  // namespace mimic
