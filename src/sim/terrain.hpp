#pragma once
// Terrain under a simulated character: flat ground, slopes, gaps, stairs or a random height
// field (seed 003 trains on slopes and gaps with a height-map input; seed 000 fine-tunes on
// stairs). A Terrain yields the MJCF of its ground and the exact height of that ground at any
// (x, y), which the "height_map" observation and the tests use.
//
// Layout: features run along +x over x in [-behind, ahead], y in [-width/2, width/2]; every kind
// is flat at z = 0 for x < start_zone (the height field: for |x|, |y| < start_zone), so episodes
// start standing near the origin. Outside that rectangle the ground is a plane at base_height().
//   slope        inclines of slope_length each from x = start_zone, then a plateau; one segment
//                rises at slope_deg (negative: downhill); more segments draw their angles
//                uniformly in [-slope_deg, slope_deg] from the seed (seed 003's "random slopes")
//   gaps         gap_count gaps of gap_width, gap_depth deep, between platforms gap_spacing long
//   stairs       step_count steps (step_height, step_depth) up, a landing, the same steps down
//   heightfield  smooth bumps 0..roughness high with a feature size, from the seed
//   walls        wall_count walls across the course every wall_spacing (the first at start_zone),
//                wall_height high and wall_thickness thick, each with one opening of
//                opening_width at a lateral place drawn from the seed (seed 000's walls course:
//                a high-level controller steers the character through the openings)
// Slopes and height fields are MuJoCo height fields sampled on a grid with `resolution` spacing
// and interpolated on MuJoCo's triangles, so height() agrees with collisions and mj_ray exactly
// (a slope's kinks are sharp where start_zone + behind and slope_length are grid multiples).
// MuJoCo 2.2's MJCF takes no elevation data: add_to() declares the grid and install() writes the
// samples into the compiled model (m->hfield_data). Gaps and stairs are axis-aligned boxes.
#include <cstdint>
#include <string>
#include <vector>

#include "sim/character_model.hpp"

struct mjModel_;

namespace mimic {

enum class TerrainKind { Flat, Slope, Gaps, Stairs, HeightField, Walls };
const char* to_string(TerrainKind kind);
// "flat", "slope", "gaps", "stairs", "heightfield", "walls"; throws Error naming the known kinds.
TerrainKind terrain_kind_from_string(const std::string& name);

struct TerrainSpec {
  TerrainKind kind = TerrainKind::Flat;
  double start_zone = 2.0;                      // flat start (m)
  double behind = 10.0, ahead = 40.0;           // extent along x (m)
  double width = 20.0;                          // extent along y (m)
  double resolution = 0.1;                      // height-field grid spacing (m)
  double slope_deg = 10.0, slope_length = 10.0;
  int slope_segments = 1;
  double gap_width = 0.5, gap_spacing = 2.0, gap_depth = 2.0;
  int gap_count = 10;
  double step_height = 0.15, step_depth = 0.3, landing = 2.0;
  int step_count = 8;
  double roughness = 0.15, feature = 1.0;       // height field: max bump height, bump size (m)
  int wall_count = 5;
  double wall_spacing = 7.0, wall_height = 1.0, wall_thickness = 0.3, opening_width = 2.0;  // (m)
  std::uint64_t seed = 0;
  bool redraw = false;  // walls only: a new course (the openings' places) at every start (Terrain::redraw)
  // > 0: a curriculum of this many levels (Terrain::set_level): level k of `levels` scales the
  // kind's difficulty by k / levels (stairs: step_height; gaps: gap_width; slope: slope_deg;
  // heightfield: roughness), the spec's value being the top level's. Walls have none.
  int levels = 0;
};

class Terrain {
 public:
  // Throws Error on a spec out of range (non-positive sizes, features beyond `ahead`, ...).
  explicit Terrain(const TerrainSpec& spec = {});
  const TerrainSpec& spec() const { return spec_; }
  // Height of the ground's top surface at (x, y), world frame (metres).
  double height(double x, double y) const;
  // The plane under everything (gap floors, ground beyond the terrain).
  double base_height() const { return base_; }
  // Where the course's last feature ends along +x: past the last incline, gap, step down or wall;
  // a height field's bumps run to `ahead`. Flat ground has no course: Error.
  double course_end() const;
  // Adds the ground to MJCF options: flat keeps the options' floor; other kinds replace it.
  void add_to(MjcfOptions& opts) const;
  // Writes the height-field samples into a model compiled from add_to's options (a no-op for
  // kinds without one); call it before stepping. Throws Error if the model has no such field.
  void install(mjModel_* m) const;
  // Walls: the course of another seed, in this terrain and in a model built from add_to's options
  // (its wall geoms moved and resized in place; positions are recomputed at the next mj_forward).
  // Every seed gives each wall two parts, so the model's geoms stay the same ones. Throws Error for
  // another kind or a model without the walls.
  void redraw(std::uint64_t seed, mjModel_* m);
  // Curriculum (spec().levels > 0): rebuilds the course at `level` in 1..levels, in this terrain and
  // in a model built from add_to's options (boxes moved and resized, a height field's samples
  // rewritten; the model was built at the top level, so every level fits its geoms). spec() then
  // holds the level's values. Throws Error without levels or for a level out of range.
  void set_level(int level, mjModel_* m);
  int level() const { return level_; }  // 0 without a curriculum; the top level until set_level

 private:
  struct Box {
    double x0, x1, y0, y1, top;  // from base_ up to top
  };
  void build();
  void build_walls();
  void move_boxes(mjModel_* m) const;
  struct Grid {  // height-field samples: row r at y0 + r * dy, column c at x0 + c * dx
    int nrow = 0, ncol = 0;
    double x0 = 0, y0 = 0, dx = 0, dy = 0, lo = 0, hi = 0;
    std::vector<double> z;  // nrow * ncol, row-major
    double at(int r, int c) const { return z[static_cast<std::size_t>(r * ncol + c)]; }
  };
  void build_slope();
  void build_gaps();
  void build_stairs();
  void build_heightfield();
  void finish_grid();
  double grid_height(double x, double y) const;

  TerrainSpec spec_;
  TerrainSpec top_;  // the spec as given: the curriculum's top level
  int level_ = 0;
  double base_ = 0.0;
  std::vector<Box> boxes_;
  Grid grid_;
};

}  // namespace mimic
