#include "env/env_factory.hpp"

#include <mutex>
#include <utility>

#include "core/config_section.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "env/context_env.hpp"
#include "env/imitation_env.hpp"
#include "env/planar_walker.hpp"
#include "motion/clip_io.hpp"
#include "env/reacher_arm.hpp"
#include "env/tracking.hpp"
#include "sim/terrain.hpp"

namespace mimic {

namespace {

EnvFactory planar_walker(ConfigSection& s) {
  PlanarWalkerConfig c;
  c.max_steps = static_cast<int>(s.integer("max_steps", c.max_steps, 1, 100'000'000));
  c.frame_skip = static_cast<int>(s.integer("frame_skip", c.frame_skip, 1, 1000));
  c.timestep = s.number("timestep", c.timestep, 1e-5, 0.1);
  c.reset_noise = s.number("reset_noise", c.reset_noise, 0, 1);
  c.control_weight = s.number("control_weight", c.control_weight, 0, 1e6);
  return [c] { return std::make_unique<PlanarWalkerEnv>(c); };
}

EnvFactory reacher(ConfigSection& s) {
  const long links = s.integer("links", 2, 2, 3);
  ReacherConfig c = links == 2 ? ReacherConfig::two_link() : ReacherConfig::three_link();
  c.observation = s.choice("observation", c.observation, {"full", "ee_to_target"});
  c.max_steps = static_cast<int>(s.integer("max_steps", c.max_steps, 1, 100'000'000));
  c.target_period = s.number("target_period", c.target_period);
  c.squared_distance = s.boolean("squared_distance", c.squared_distance);
  c.control_weight = s.number("control_weight", c.control_weight, 0, 1e6);
  return [c] { return std::make_unique<ReacherArmEnv>(c); };
}

// A data file the config names: beside the config when it is there (a run or model directory
// holds its own clips), else as given (absolute, or relative to the working directory), else under
// the shared data directory.
std::filesystem::path data_path(const std::string& given, const char* key, const YamlReader& reader) { return env_data_path(given, key, reader); }

// Makers registered by higher layers (register_env), by name, in the order registered.
std::vector<std::pair<std::string, EnvMaker>>& registered() {
  static std::vector<std::pair<std::string, EnvMaker>> makers;
  return makers;
}
std::mutex& registry_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace

std::filesystem::path env_data_path(const std::string& given, const char* key, const YamlReader& reader) {
  const std::filesystem::path p(given), config_dir = std::filesystem::path(reader.source()).parent_path();
  if (p.is_relative() && !config_dir.empty() && std::filesystem::exists(config_dir / p)) return config_dir / p;
  if (std::filesystem::exists(p)) return p;
  const std::filesystem::path shared = shared_data_dir();
  if (!shared.empty() && p.is_relative() && std::filesystem::exists(shared / p)) return shared / p;
  throw Error(reader.source() + ": 'env." + key + "': " + given + " not found (looked beside the config, in the working directory and under " +
              (shared.empty() ? std::string("the shared data directory, which is absent: set MIMIC_DATA") : shared.string()) + ")");
}

namespace {

// A DeepMimic character (with its PD file when one lies beside it) and a clip for it.
std::shared_ptr<const CharacterModel> load_character(const std::filesystem::path& ch_path) {
  const std::filesystem::path ctrl = ch_path.parent_path() / (ch_path.stem().string() + "_ctrl.txt");
  return std::make_shared<const CharacterModel>(
      CharacterModel::from_deepmimic(ch_path, std::filesystem::exists(ctrl) ? ctrl : std::filesystem::path{}));
}

std::shared_ptr<const Clip> load_clip(const std::filesystem::path& clip_path, const std::filesystem::path& ch_path) {
  LoadOptions load;
  load.character = ch_path;
  return std::make_shared<const Clip>(load_motion(clip_path, load));
}

// Seed 004's projectile test (sim/perturbation.hpp): cubes launched at the torso.
ProjectileSpec read_projectiles(ConfigSection& parent, const YamlReader& reader, const char* path) {
  ProjectileSpec p;
  ConfigSection s(reader, parent.child("projectiles"), path);
  p.enabled = s.boolean("enabled", p.enabled);
  p.mass = s.number("mass", p.mass, 1e-6, 1e6);
  p.size = s.number("size", p.size, 1e-3, 10);
  p.speed = s.number("speed", p.speed, 0, 1e3);
  p.distance = s.number("distance", p.distance, 1e-3, 100);
  p.every = static_cast<int>(s.integer("every", p.every, 0, 100'000));  // 0: only on demand (Controller::throw_cube)
  p.target = s.text("target", p.target);
  s.finish();
  return p;
}

// The terrain (sim/terrain.hpp): terrain: {kind: flat | slope | gaps | stairs | heightfield | walls, ...}.
TerrainSpec read_terrain(ConfigSection& parent, const YamlReader& reader) {
  TerrainSpec t;
  ConfigSection s(reader, parent.child("terrain"), "env.terrain");
  t.kind = terrain_kind_from_string(s.choice("kind", "flat", {"flat", "slope", "gaps", "stairs", "heightfield", "walls"}));
  t.redraw = s.boolean("redraw", t.redraw);
  t.levels = static_cast<int>(s.integer("levels", t.levels, 0, 1000));
  t.start_zone = s.number("start_zone", t.start_zone, 0, 1e3);
  t.behind = s.number("behind", t.behind, 0, 1e4);
  t.ahead = s.number("ahead", t.ahead, 0, 1e4);
  t.width = s.number("width", t.width, 0, 1e4);
  t.resolution = s.number("resolution", t.resolution, 1e-3, 10);
  t.slope_deg = s.number("slope_deg", t.slope_deg, -60, 60);
  t.slope_length = s.number("slope_length", t.slope_length, 0, 1e4);
  t.slope_segments = static_cast<int>(s.integer("slope_segments", t.slope_segments, 1, 10'000));
  t.gap_width = s.number("gap_width", t.gap_width, 0, 100);
  t.gap_spacing = s.number("gap_spacing", t.gap_spacing, 0, 1e3);
  t.gap_depth = s.number("gap_depth", t.gap_depth, 0, 1e3);
  t.gap_count = static_cast<int>(s.integer("gap_count", t.gap_count, 0, 10'000));
  t.step_height = s.number("step_height", t.step_height, 0, 10);
  t.step_depth = s.number("step_depth", t.step_depth, 0, 100);
  t.landing = s.number("landing", t.landing, 0, 1e3);
  t.step_count = static_cast<int>(s.integer("step_count", t.step_count, 0, 10'000));
  t.roughness = s.number("roughness", t.roughness, 0, 100);
  t.feature = s.number("feature", t.feature, 1e-3, 1e3);
  t.wall_count = static_cast<int>(s.integer("wall_count", t.wall_count, 0, 10'000));
  t.wall_spacing = s.number("wall_spacing", t.wall_spacing, 0, 1e3);
  t.wall_height = s.number("wall_height", t.wall_height, 0, 100);
  t.wall_thickness = s.number("wall_thickness", t.wall_thickness, 0, 100);
  t.opening_width = s.number("opening_width", t.opening_width, 0, 1e3);
  t.seed = s.seed("seed", t.seed);
  s.finish();
  return t;
}

// Pushes (sim/perturbation.hpp): pushes: [{link: chest, force: [0, 300, 0], start: 2, duration: 0.1}, ...],
// times from each episode's start, forces in newtons in the world frame.
std::vector<PushSpec> read_pushes(ConfigSection& parent, const YamlReader& reader) {
  const YAML::Node list = parent.child("pushes");
  std::vector<PushSpec> pushes;
  if (!list.IsDefined() || list.IsNull()) return pushes;
  if (!list.IsSequence()) reader.fail(list, "'env.pushes': expected a list of {link, force, start, duration}");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = "env.pushes[" + std::to_string(i) + "]";
    if (!list[i].IsMap()) reader.fail(list[i], "'" + where + "': expected a mapping {link, force, start, duration}");
    ConfigSection s(reader, list[i], where);
    PushSpec p;
    p.link = s.text("link", "");
    if (p.link.empty()) reader.fail(list[i], "'" + where + "': missing 'link' (the body to push)");
    if (!s.has("force")) reader.fail(list[i], "'" + where + "': missing 'force' ([x, y, z] newtons, world frame)");
    p.force = reader.vec<3>(s.child("force"), s.name("force"));
    p.start = s.number("start", p.start, 0, 1e6);
    p.duration = s.number("duration", p.duration, 0, 1e6);
    s.finish();
    pushes.push_back(p);
  }
  return pushes;
}

// The character environment's keys, shared by both humanoid environments, read into the struct
// that uses them (CharacterEnvConfig); `c` holds each environment's defaults.
void read_character_env(ConfigSection& s, const YamlReader& reader, CharacterEnvConfig& c) {
  c.observations.names = s.texts("observations", c.observations.names);
  c.observations.link_history = static_cast<int>(s.integer("link_history", c.observations.link_history, 1, 64));
  c.observations.height_map_size = static_cast<int>(s.integer("height_map_size", c.observations.height_map_size, 1, 101));
  c.observations.height_map_spacing = s.number("height_map_spacing", c.observations.height_map_spacing, 1e-3, 10);
  c.observations.height_map_ahead = s.number("height_map_ahead", c.observations.height_map_ahead, -100, 100);
  c.max_seconds = s.number("max_seconds", c.max_seconds, 1e-3, 1e6);
  // `fall_links: all` (every body; allow_clip_contacts then spares those the clip rests on) or a list.
  if (const YAML::Node links = s.child("fall_links"); links.IsScalar()) {
    if (links.Scalar() != kAllFallLinks) reader.fail(links, s.name("fall_links") + ": a list of bodies, or all (every body); not '" + links.Scalar() + "'");
    c.fall_links = {kAllFallLinks};
  } else {
    c.fall_links = s.texts("fall_links", c.fall_links);
  }
  c.allow_clip_contacts = s.boolean("allow_clip_contacts", c.allow_clip_contacts);
  c.early_termination = s.boolean("early_termination", c.early_termination);
  c.fall_height = s.number("fall_height", c.fall_height, 0, 1);
  c.max_drift = s.number("max_drift", c.max_drift, 0, 1e6);
  c.lift_starts = s.boolean("lift_starts", c.lift_starts);
  c.start_momentum.window = s.number("start_momentum_window", c.start_momentum.window, 0, 10);
  c.start_momentum.statistic = s.choice("start_momentum_statistic", "mean", {"mean", "median"}) == "median"
                                   ? StartMomentumSmoothing::Statistic::Median
                                   : StartMomentumSmoothing::Statistic::Mean;
  c.start_momentum.linear = s.boolean("start_momentum_linear", c.start_momentum.linear);
  for (const char* key : {"start_momentum_statistic", "start_momentum_linear"})
    if (s.child(key).IsDefined() && !s.child("start_momentum_window").IsDefined())
      reader.fail(s.child(key), std::string("'env.") + key +
                                    "' shapes start_momentum_window's smoothing: it needs a start_momentum_window (0 turns it off)");
  c.sim.physics_hz = s.number("physics_hz", c.sim.physics_hz, 1, 100'000);
  c.sim.control_hz = s.number("control_hz", c.sim.control_hz, 1, 10'000);
  // What a joint's torque limit bounds (sim/world.hpp PdLimit): `spring`, the default the committed
  // models were trained under, or `total`, DeepMimic's rule.
  c.sim.pd_limit = s.choice("pd_limit", "spring", {"spring", "total"}) == "total" ? PdLimit::Total : PdLimit::Spring;
  c.terrain = read_terrain(s, reader);
  c.pushes = read_pushes(s, reader);
  c.projectiles = read_projectiles(s, reader, "env.projectiles");
}

// The character and its clips, looked up as data_path says.
struct CharacterData {
  std::filesystem::path path;
  std::shared_ptr<const CharacterModel> model;
};
CharacterData read_character(ConfigSection& s, const YamlReader& reader) {
  const std::filesystem::path path = data_path(s.text("character", "deepmimic/characters/humanoid3d.txt"), "character", reader);
  return {path, load_character(path)};
}

EnvFactory imitation(ConfigSection& s, const YamlReader& reader) {
  ImitationEnvConfig c;
  const CharacterData ch = read_character(s, reader);
  // One clip, or a list of them for starts from all (seed 004's integrated learning).
  const std::vector<std::string> clip_files = s.child("clip").IsSequence()
                                                  ? s.texts("clip", {})
                                                  : std::vector<std::string>{s.text("clip", "deepmimic/motions/humanoid3d_walk.txt")};
  if (clip_files.empty()) reader.fail(s.child("clip"), "'env.clip': an empty list (give one clip or several)");
  c.init = s.choice("init", "mocap", {"mocap", "fixed"}) == "mocap" ? ImitationEnvConfig::Init::Mocap : ImitationEnvConfig::Init::FixedPose;
  read_character_env(s, reader, c.env);
  c.alive_bonus = s.number("alive_bonus", c.alive_bonus, 0, 1e6);
  c.forward_weight = s.number("forward_weight", c.forward_weight, 0, 1e6);
  c.target_speed = s.number("target_speed", c.target_speed, 0, 100);
  c.lateral_weight = s.number("lateral_weight", c.lateral_weight, 0, 1e6);
  c.control_weight = s.number("control_weight", c.control_weight, 0, 1e6);
  c.init_noise = s.number("init_noise", c.init_noise, 0, 3);
  c.fallen_starts = s.number("fallen_starts", c.fallen_starts, 0, 1);
  const std::vector<std::string> start_files = s.texts("start_clips", {});
  c.start_clip_share = s.number("start_clip_share", start_files.empty() ? 0.0 : 0.75, 0, 1);
  if (c.start_clip_share > 0 && start_files.empty())
    reader.fail(s.child("start_clip_share"), "'env.start_clip_share': no 'env.start_clips' to start from");
  if (c.start_clip_share > 0 && c.init != ImitationEnvConfig::Init::Mocap)
    reader.fail(s.child("start_clips"), "'env.start_clips' replace mocap starts: they need 'init: mocap'");
  c.goal = s.choice("goal", "none", {"none", "heading"}) == "heading" ? ImitationEnvConfig::Goal::Heading : ImitationEnvConfig::Goal::None;
  c.goal_speed = s.number("goal_speed", c.goal_speed, 0, 100);
  c.goal_period = s.number("goal_period", c.goal_period, 1e-3, 1e6);
  c.goal_weight = s.number("goal_weight", c.goal_weight, 0, 1e6);
  c.goal_sharpness = s.number("goal_sharpness", c.goal_sharpness, 0, 1e6);
  c.goal_facing = s.number("goal_facing", c.goal_facing, 0, 1);
  c.goal_turn = s.number("goal_turn", c.goal_turn, 0, 180);
  std::vector<std::shared_ptr<const Clip>> clips;
  for (const std::string& f : clip_files) clips.push_back(load_clip(data_path(f, "clip", reader), ch.path));
  std::vector<std::shared_ptr<const Clip>> start_clips;
  for (const std::string& f : start_files) start_clips.push_back(load_clip(data_path(f, "start_clips", reader), ch.path));
  return [model = ch.model, clips, c, start_clips] { return std::unique_ptr<Env>(make_imitation_env(*model, clips, c, start_clips)); };
}

EnvFactory tracking(ConfigSection& s, const YamlReader& reader) {
  TrackingConfig c;
  const CharacterData ch = read_character(s, reader);
  const std::string clip_file = s.text("clip", "deepmimic/motions/humanoid3d_walk.txt");
  c.init = s.choice("init", "reference", {"reference", "fixed"}) == "reference" ? TrackingConfig::Init::Reference
                                                                                 : TrackingConfig::Init::Fixed;
  read_character_env(s, reader, c.env);
  c.com_term = s.choice("com_term", "position", {"position", "velocity"}) == "velocity" ? ComTerm::Velocity : ComTerm::Position;
  c.resync_root = s.boolean("resync_root", c.resync_root);
  ConfigSection w(reader, s.child("weights"), "env.weights");
  c.weights = {w.number("pose", c.weights.pose, 0, 1e6), w.number("velocity", c.weights.velocity, 0, 1e6),
               w.number("end_effector", c.weights.end_effector, 0, 1e6), w.number("com", c.weights.com, 0, 1e6),
               w.number("root", c.weights.root, 0, 1e6)};
  w.finish();
  ConfigSection k(reader, s.child("scales"), "env.scales");
  c.scales = {k.number("pose", c.scales.pose, 0, 1e6), k.number("velocity", c.scales.velocity, 0, 1e6),
              k.number("end_effector", c.scales.end_effector, 0, 1e6), k.number("com", c.scales.com, 0, 1e6),
              k.number("root", c.scales.root, 0, 1e6)};
  k.finish();
  auto clip = load_clip(data_path(clip_file, "clip", reader), ch.path);
  return [model = ch.model, clip, c] { return std::unique_ptr<Env>(make_tracking_env(*model, clip, c)); };
}

// The environments this layer builds: each name once, with whether it simulates a character
// (terrain, pushes and cubes apply) and its maker.
struct BuiltInEnv {
  const char* name;
  bool has_character;
  EnvFactory (*make)(ConfigSection&, const YamlReader&);
  bool listed;  // in messages and help (humanoid_forward: imitation's name in models saved before it had one)
};
constexpr BuiltInEnv kBuiltInEnvs[] = {
    {"imitation", true, imitation, true},
    {"tracking", true, tracking, true},
    {"planar_walker", false, [](ConfigSection& s, const YamlReader&) { return planar_walker(s); }, true},
    {"reacher", false, [](ConfigSection& s, const YamlReader&) { return reacher(s); }, true},
    {"humanoid_forward", true, imitation, false},
};

const BuiltInEnv* built_in_env(const std::string& name) {
  for (const BuiltInEnv& e : kBuiltInEnvs)
    if (name == e.name) return &e;
  return nullptr;
}

}  // namespace

std::string env_names() {
  std::string names;
  for (const BuiltInEnv& e : kBuiltInEnvs)
    if (e.listed) names += (names.empty() ? "" : ", ") + std::string(e.name);
  const std::lock_guard lock(registry_mutex());
  for (const auto& [name, make] : registered()) names += ", " + name;
  return names;
}

bool env_has_character(const std::string& name) {
  const BuiltInEnv* e = built_in_env(name);
  return e != nullptr && e->has_character;
}

ModelEnvSection model_env_section(const std::filesystem::path& dir) {
  const std::filesystem::path config = dir / "config.yaml";
  YamlReader reader(config.string());
  YAML::Node env = reader.parse(read_text_file(config), config.string())["env"];
  return {env, std::move(reader)};
}

std::string model_env_name(const std::filesystem::path& dir) {
  const YAML::Node env = model_env_section(dir).env;
  return env.IsMap() && env["name"].IsScalar() ? env["name"].as<std::string>() : "";
}

void register_env(const std::string& name, EnvMaker make) {
  const std::lock_guard lock(registry_mutex());
  for (const auto& [known, maker] : registered())
    if (known == name) return;
  registered().emplace_back(name, std::move(make));
}

EnvFactory make_env_factory(const YAML::Node& env, const YamlReader& reader) {
  ConfigSection s(reader, env, "env");
  std::vector<std::string> names;
  for (const BuiltInEnv& e : kBuiltInEnvs) names.emplace_back(e.name);
  EnvMaker other;
  {
    const std::lock_guard lock(registry_mutex());
    for (const auto& [known, maker] : registered()) names.push_back(known);
  }
  const std::string name = s.choice("name", "", names);
  if (name.empty()) reader.fail(env, "'env': missing 'name' (one of " + env_names() + ")");
  {
    const std::lock_guard lock(registry_mutex());
    for (const auto& [known, maker] : registered())
      if (known == name) other = maker;
  }
  EnvFactory f;
  try {
    f = other ? other(s, reader) : built_in_env(name)->make(s, reader);
  } catch (const ParseError&) {
    throw;
  } catch (const Error& e) {
    reader.fail(env, e.what());
  }
  // Any environment may carry seed 000's behaviour context: context: {count: K, period: steps,
  // starts: any | by_context}; by_context starts each episode from its context's clip (clip i of
  // an imitation env's list for context i).
  const YAML::Node context = s.child("context");
  if (context.IsDefined()) {
    ConfigSection c(reader, context, "env.context");
    const int count = static_cast<int>(c.integer("count", 2, 2, 1024));
    const int period = static_cast<int>(c.integer("period", 0, 0, 100'000'000));
    const bool by_context = c.choice("starts", "any", {"any", "by_context"}) == "by_context";
    c.finish();
    f = [inner = f, count, period, by_context] {
      return std::unique_ptr<Env>(std::make_unique<ContextEnv>(inner(), count, period, by_context));
    };
  }
  s.finish();
  try {
    (void)f();
  } catch (const KeyError& e) {  // at the key's line where the config sets it
    const YAML::Node key = s.child(e.key().c_str());
    reader.fail(key.IsDefined() ? key : env, "'env." + e.key() + "' (" + name + "): " + e.message());
  } catch (const Error& e) {
    reader.fail(env, "'env' (" + name + "): " + e.what());
  }
  return f;
}

}  // namespace mimic
