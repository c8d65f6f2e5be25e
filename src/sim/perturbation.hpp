#pragma once
// External perturbations of a simulated character: pushes (a force on a link for a while) and
// the projectile test of seed 004 section 6.4 (cubes of 0.2 m side and a fixed mass launched at
// a uniformly sampled point of the torso every frame at 0.2 m/s; robustness = frames survived
// versus cube mass).
#include <random>
#include <string>
#include <vector>

#include "sim/world.hpp"

namespace mimic {

struct PushSpec {
  std::string link;           // body (joint) name of the character
  Vec3 force = Vec3::Zero();  // world frame (N), at the link's centre of mass
  double start = 0.0;         // seconds after the episode start
  double duration = 0.0;      // seconds
};

// Pushes through mjData::xfrc_applied. Forces are set once per control step; a push covering
// part of a step is scaled by the covered fraction, so each push delivers exactly force * duration.
class Pusher {
 public:
  // Throws Error naming a link the character does not have, or a negative duration.
  Pusher(const World& world, std::vector<PushSpec> pushes);
  // Sets the pushed links' forces for the control step [t, t + dt), t since the episode start.
  void apply(World& world, double t, double dt) const;
  // Removes the pushed links' forces.
  void clear(World& world) const;
  const std::vector<PushSpec>& pushes() const { return pushes_; }

 private:
  std::vector<PushSpec> pushes_;
  std::vector<int> body_;  // MuJoCo body per push
};

struct ProjectileSpec {
  bool enabled = false;
  double mass = 1.0;              // kg: the variable of seed 004's Fig. 7
  double size = 0.2;              // cube side (m), seed 004
  double speed = 0.2;             // launch speed (m/s), seed 004
  double distance = 0.5;          // launch point to aim point (m, >= size); seed 004 does not say
  int every = 1;                  // launch every k-th control step; seed 004: every frame. 0: only on demand (launch())
  std::string target = "chest";   // the torso link aimed at (this default: the root link of a body without a chest)
  double min_elevation_deg = -15.0, max_elevation_deg = 45.0;  // launch directions (azimuth uniform)
  double linger = 0.5;            // seconds a cube stays in the scene after its flight ends
  int pool = 0;                   // cubes in the model; 0: enough for every flight plus linger (on demand: 4)
  std::uint64_t seed = 0;         // aim and direction draws (CharacterEnv reseeds on reset(rng))
};

// Cubes needed so that round-robin reuse never cuts a flight or linger short.
int projectile_pool_size(const ProjectileSpec& spec, double control_hz);

struct ProjectileStats {
  int launched = 0, hits = 0, misses = 0;  // misses: flights that ended without touching the character
};

// A fixed pool of free box bodies, parked far away and held there (gravity cancelled) when idle.
// A launched cube flies in a straight line at `speed` (gravity cancelled by xfrc_applied: at
// 0.2 m/s a ballistic cube would drop metres before arriving) until it touches anything (a hit
// if that is the character) or comes within half a side of its aim point untouched (a miss: the
// torso moved away); then it falls freely and is parked again `linger` seconds later. Cubes
// collide with the character and the ground but not with each other (contype 4, conaffinity 3).
class ProjectileLauncher {
 public:
  // Adds the pool's MJCF to `opts.extra_worldbody` and room for its contacts to `opts`; no-op unless spec.enabled.
  static void add_to(MjcfOptions& opts, const ProjectileSpec& spec, double control_hz);
  // Binds to a World built with add_to's options; throws Error if the pool or target is missing.
  ProjectileLauncher(const World& world, const ProjectileSpec& spec);
  // Parks every cube and clears the statistics (call after World::set_state).
  void reset(World& world);
  void reseed(std::uint64_t seed) { rng_.seed(seed); }
  // Before a control step: launches a cube on every `every`-th call (none when `every` is 0).
  void before_step(World& world);
  // After a control step: ends flights on contact, counts hits, parks cubes past their linger.
  void after_step(World& world);
  // Launches the next cube of the pool at `aim`, from aim + distance * dir (dir normalised);
  // returns its pool index.
  int launch(World& world, const Vec3& aim, const Vec3& dir);
  // A uniformly sampled point inside the target link's geom, and a random launch direction.
  Vec3 sample_aim(const World& world);
  Vec3 sample_direction();

  const ProjectileSpec& spec() const { return spec_; }
  const ProjectileStats& stats() const { return stats_; }
  int pool_size() const { return static_cast<int>(cubes_.size()); }
  int body(int k) const { return cubes_[static_cast<std::size_t>(k)].body; }
  bool flying(int k) const { return cubes_[static_cast<std::size_t>(k)].state == State::Flying; }

 private:
  enum class State { Parked, Flying, Landed };
  struct Cube {
    int body = -1, geom = -1, qpos = -1, dof = -1;
    State state = State::Parked;
    double since = 0.0;  // launch or landing time
    Vec3 velocity = Vec3::Zero();
  };
  void park(World& world, Cube& c, int k) const;
  void set_force(World& world, const Cube& c, bool cancel_gravity) const;
  void end_flight(World& world, Cube& c, bool hit);

  ProjectileSpec spec_;
  std::vector<Cube> cubes_;
  std::vector<char> character_body_;  // per MuJoCo body
  int target_body_ = -1, target_geom_ = -1;
  int next_ = 0, calls_ = 0;
  ProjectileStats stats_;
  std::mt19937_64 rng_;
};

}  // namespace mimic
