#include "sim/perturbation.hpp"

#include <fmt/format.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace mimic {

Pusher::Pusher(const World& world, std::vector<PushSpec> pushes) : pushes_(std::move(pushes)) {
  for (const PushSpec& p : pushes_) {
    if (world.character().skeleton.find(p.link) < 0)
      throw Error("push: character '" + world.character().name + "' has no link '" + p.link + "'");
    if (!(p.duration >= 0) || !p.force.allFinite()) throw Error("push on '" + p.link + "': need a finite force and duration >= 0");
    body_.push_back(mj_name2id(world.model(), mjOBJ_BODY, p.link.c_str()));
  }
}

void Pusher::clear(World& world) const {
  for (int b : body_)
    for (int k = 0; k < 3; ++k) world.data()->xfrc_applied[6 * b + k] = 0.0;
}

void Pusher::apply(World& world, double t, double dt) const {
  mjData* d = world.data();
  clear(world);
  for (std::size_t i = 0; i < pushes_.size(); ++i) {
    const PushSpec& p = pushes_[i];
    const double covered = std::min(t + dt, p.start + p.duration) - std::max(t, p.start);
    if (covered <= 0 || dt <= 0) continue;
    for (int k = 0; k < 3; ++k) d->xfrc_applied[6 * body_[i] + k] += p.force[k] * covered / dt;
  }
}

namespace {

// Longest flight: by then the cube's centre is half a side from its aim point inside the torso,
// so a cube that has touched nothing has missed (the torso moved away).
double max_flight(const ProjectileSpec& spec) { return (spec.distance - spec.size / 2) / spec.speed; }

Vec3 park_position(int k) { return Vec3(1000.0 + 2.0 * k, 1000.0, 100.0); }
std::string cube_name(int k) { return fmt::format("projectile{}", k); }

void check(const ProjectileSpec& s) {
  if (!(s.mass > 0 && s.size > 0 && s.speed > 0 && s.distance >= s.size && s.linger >= 0) || s.every < 0 || s.pool < 0)
    throw Error("projectiles: need positive mass, size and speed, every >= 0 (0: on demand), distance >= size, linger >= 0, pool >= 0");
  if (!(s.min_elevation_deg <= s.max_elevation_deg) || std::abs(s.min_elevation_deg) > 90 || std::abs(s.max_elevation_deg) > 90)
    throw Error("projectiles: need -90 <= min_elevation_deg <= max_elevation_deg <= 90");
}

}  // namespace

// Cubes launched on demand (every = 0): a few in flight or lingering at once; a launch beyond them
// takes the oldest.
constexpr int kOnDemandPool = 4;

int projectile_pool_size(const ProjectileSpec& spec, double control_hz) {
  if (spec.every == 0) return kOnDemandPool;
  const double life = max_flight(spec) + spec.linger + 2.0 / control_hz;
  return std::max(1, static_cast<int>(std::ceil(life * control_hz / spec.every)) + 1);
}

void ProjectileLauncher::add_to(MjcfOptions& opts, const ProjectileSpec& spec, double control_hz) {
  if (!spec.enabled) return;
  check(spec);
  const int n = spec.pool > 0 ? spec.pool : projectile_pool_size(spec, control_hz);
  opts.visual_extent = 3.0;  // (the parked cubes are a kilometre away; a person is a metre or two)
  // Room for the cubes' contacts and their constraint rows (4 a contact of condim 3), by the pool.
  // Measured: at most 16 contacts (64 rows) in 10 s of 100 kg cubes on the walk, 59 (236) with a
  // get-up writhing among 60 kg ones; MuJoCo prints a warning where the room runs out. Not more:
  // MuJoCo 2.2 clears about 12 njmax² bytes for every MjData it makes (200 MB at njmax 4,000,
  // which made loading a skill with cubes take seconds).
  opts.max_contacts += 2 * n;
  opts.max_constraints += 8 * n;
  const double h = spec.size / 2;
  for (int k = 0; k < n; ++k) {
    const Vec3 p = park_position(k);
    opts.extra_worldbody += fmt::format(
        "    <body name=\"{0}\" pos=\"{1:.9g} {2:.9g} {3:.9g}\"><freejoint name=\"{0}\"/>"
        "<geom name=\"{0}\" type=\"box\" size=\"{4:.9g} {4:.9g} {4:.9g}\" mass=\"{5:.9g}\" contype=\"4\" conaffinity=\"3\" rgba=\".85 .35 .2 1\"/></body>\n",
        cube_name(k), p.x(), p.y(), p.z(), h, spec.mass);
  }
}

ProjectileLauncher::ProjectileLauncher(const World& world, const ProjectileSpec& spec) : spec_(spec), rng_(spec.seed) {
  check(spec_);
  const mjModel* m = world.model();
  for (int k = 0;; ++k) {
    Cube c;
    c.body = mj_name2id(m, mjOBJ_BODY, cube_name(k).c_str());
    if (c.body < 0) break;
    const int j = m->body_jntadr[c.body];
    c.geom = m->body_geomadr[c.body];
    c.qpos = m->jnt_qposadr[j], c.dof = m->jnt_dofadr[j];
    cubes_.push_back(c);
  }
  if (cubes_.empty()) throw Error("projectiles: the model has no projectile pool (build it with ProjectileLauncher::add_to)");
  const Skeleton& skeleton = world.character().skeleton;
  // The default target on a body without a chest (DeepMimic's dog): its root link.
  if (spec_.target == ProjectileSpec{}.target && skeleton.find(spec_.target) < 0 && !skeleton.joints.empty())
    spec_.target = skeleton.joints.front().name;
  target_body_ = mj_name2id(m, mjOBJ_BODY, spec_.target.c_str());
  if (target_body_ < 0 || skeleton.find(spec_.target) < 0 || m->body_geomnum[target_body_] < 1)
    throw Error("projectiles: character '" + world.character().name + "' has no link '" + spec_.target + "' with a geom to aim at");
  target_geom_ = m->body_geomadr[target_body_];
  character_body_.assign(static_cast<std::size_t>(m->nbody), 0);
  for (const Joint& j : world.character().skeleton.joints)
    character_body_[static_cast<std::size_t>(mj_name2id(m, mjOBJ_BODY, j.name.c_str()))] = 1;
}

void ProjectileLauncher::set_force(World& world, const Cube& c, bool cancel_gravity) const {
  const mjModel* m = world.model();
  for (int k = 0; k < 3; ++k)
    world.data()->xfrc_applied[6 * c.body + k] = cancel_gravity ? -m->body_mass[c.body] * m->opt.gravity[k] : 0.0;
}

void ProjectileLauncher::park(World& world, Cube& c, int k) const {
  mjData* d = world.data();
  const Vec3 p = park_position(k);
  for (int i = 0; i < 3; ++i) d->qpos[c.qpos + i] = p[i];
  d->qpos[c.qpos + 3] = 1, d->qpos[c.qpos + 4] = d->qpos[c.qpos + 5] = d->qpos[c.qpos + 6] = 0;
  for (int i = 0; i < 6; ++i) d->qvel[c.dof + i] = 0;
  set_force(world, c, true);  // idle cubes hover where they are parked
  c.state = State::Parked;
}

void ProjectileLauncher::reset(World& world) {
  for (std::size_t k = 0; k < cubes_.size(); ++k) park(world, cubes_[k], static_cast<int>(k));
  mj_forward(world.model(), world.data());
  stats_ = {};
  next_ = calls_ = 0;
}

Vec3 ProjectileLauncher::sample_aim(const World& world) {
  const mjModel* m = world.model();
  const mjData* d = world.data();
  const mjtNum* s = m->geom_size + 3 * target_geom_;
  const int type = m->geom_type[target_geom_];
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // Rejection sampling in the geom's bounding box: uniform over its volume.
  const double r = s[0];
  Vec3 half = type == mjGEOM_SPHERE ? Vec3(r, r, r) : type == mjGEOM_CAPSULE ? Vec3(r, r, s[1] + r)
            : type == mjGEOM_CYLINDER ? Vec3(r, r, s[1]) : Vec3(s[0], s[1], s[2]);
  Vec3 local;
  for (int tries = 0; tries < 1000; ++tries) {
    local = Vec3(u(rng_) * half.x(), u(rng_) * half.y(), u(rng_) * half.z());
    const double radial = std::hypot(local.x(), local.y());
    const bool inside = type == mjGEOM_SPHERE ? local.norm() <= r
                      : type == mjGEOM_CAPSULE ? Vec3(local.x(), local.y(), std::max(0.0, std::abs(local.z()) - s[1])).norm() <= r
                      : type == mjGEOM_CYLINDER ? radial <= r
                      : type == mjGEOM_ELLIPSOID ? local.cwiseQuotient(half).norm() <= 1 : true;
    if (inside) break;
  }
  const Eigen::Map<const Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor>> rot(d->geom_xmat + 9 * target_geom_);
  return Vec3(d->geom_xpos[3 * target_geom_], d->geom_xpos[3 * target_geom_ + 1], d->geom_xpos[3 * target_geom_ + 2]) + rot * local;
}

Vec3 ProjectileLauncher::sample_direction() {
  std::uniform_real_distribution<double> azimuth(-kPi, kPi);
  // Elevation with density ~ cos(e), as for uniform points on the sphere's band.
  const double s0 = std::sin(deg_to_rad(spec_.min_elevation_deg)), s1 = std::sin(deg_to_rad(spec_.max_elevation_deg));
  const double e = std::asin(std::uniform_real_distribution<double>(s0, s1)(rng_));
  const double a = azimuth(rng_);
  return Vec3(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
}

int ProjectileLauncher::launch(World& world, const Vec3& aim, const Vec3& dir) {
  const int k = next_;
  next_ = (next_ + 1) % pool_size();
  Cube& c = cubes_[static_cast<std::size_t>(k)];
  if (c.state == State::Flying) end_flight(world, c, false);  // pool too small: the oldest flight is cut
  mjData* d = world.data();
  const Vec3 u = dir.normalized();
  const Vec3 start = aim + spec_.distance * u;
  c.velocity = -spec_.speed * u;
  for (int i = 0; i < 3; ++i) d->qpos[c.qpos + i] = start[i], d->qvel[c.dof + i] = c.velocity[i], d->qvel[c.dof + 3 + i] = 0;
  d->qpos[c.qpos + 3] = 1, d->qpos[c.qpos + 4] = d->qpos[c.qpos + 5] = d->qpos[c.qpos + 6] = 0;
  set_force(world, c, true);
  c.state = State::Flying;
  c.since = d->time;
  ++stats_.launched;
  return k;
}

void ProjectileLauncher::before_step(World& world) {
  if (spec_.every == 0 || calls_++ % spec_.every != 0) return;
  const Vec3 aim = sample_aim(world);
  launch(world, aim, sample_direction());
}

void ProjectileLauncher::end_flight(World& world, Cube& c, bool hit) {
  set_force(world, c, false);
  c.state = State::Landed;
  c.since = world.data()->time;
  ++(hit ? stats_.hits : stats_.misses);
}

void ProjectileLauncher::after_step(World& world) {
  const mjModel* m = world.model();
  const mjData* d = world.data();
  // Per geom: touching the character (1), touching anything else (2).
  std::vector<unsigned> touch(static_cast<std::size_t>(m->ngeom), 0);
  for (int i = 0; i < d->ncon; ++i) {
    const int g1 = d->contact[i].geom1, g2 = d->contact[i].geom2;
    touch[static_cast<std::size_t>(g1)] |= character_body_[static_cast<std::size_t>(m->geom_bodyid[g2])] ? 1u : 2u;
    touch[static_cast<std::size_t>(g2)] |= character_body_[static_cast<std::size_t>(m->geom_bodyid[g1])] ? 1u : 2u;
  }
  for (std::size_t k = 0; k < cubes_.size(); ++k) {
    Cube& c = cubes_[k];
    if (c.state == State::Flying) {
      const unsigned t = touch[static_cast<std::size_t>(c.geom)];
      // A flying cube keeps its velocity exactly; any change means it touched something between
      // the contact checks (fast cubes can bounce off within one control step).
      const Vec3 v(d->qvel[c.dof], d->qvel[c.dof + 1], d->qvel[c.dof + 2]);
      const bool deflected = (v - c.velocity).norm() > 1e-3 * spec_.speed;
      if (t != 0 || deflected) end_flight(world, c, (t & 1u) != 0 || (t & 2u) == 0);
      else if (d->time - c.since > max_flight(spec_)) end_flight(world, c, false);
    } else if (c.state == State::Landed && d->time - c.since >= spec_.linger - 1e-9) {
      park(world, c, static_cast<int>(k));
    }
  }
}

}  // namespace mimic
