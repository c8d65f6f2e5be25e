#include <algorithm>
#include <sstream>

#include "control/navigation.hpp"
#include "control/skill_impl.hpp"
#include "core/config_override.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/yaml_reader.hpp"
#include "env/character_env.hpp"
#include "env/context_env.hpp"
#include "sim/mujoco_load.hpp"

namespace mimic {

namespace {

std::vector<ObservationSlice> parse_layout(const std::string& text, const ArrayTable& t) {
  std::vector<ObservationSlice> layout;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream fields(line);
    ObservationSlice s;
    std::string rest;
    if (!(fields >> s.name >> s.offset >> s.size) || (fields >> rest) || s.offset < 0 || s.size < 0)
      t.fail("array 'observation.layout': line '" + line + "' is not 'NAME OFFSET SIZE'");
    layout.push_back(s);
  }
  return layout;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) out.push_back(line);
  return out;
}

std::string layout_text(const std::vector<ObservationSlice>& layout) {
  std::string s;
  for (const ObservationSlice& p : layout) s += (s.empty() ? "" : ", ") + p.name + " " + std::to_string(p.size);
  return s.empty() ? "(none)" : s;
}

Network::Activation activation_of(const ArrayTable& t, const std::string& name) {
  const std::string a = t.text(name);
  if (a == "relu") return Network::Activation::Relu;
  if (a == "tanh") return Network::Activation::Tanh;
  t.fail("array '" + name + "' is '" + a + "', expected relu or tanh");
}

constexpr int kMaxSize = 1 << 20;

}  // namespace

std::unique_ptr<Skill::Impl> read_skill_networks(std::string_view bytes, const std::filesystem::path& networks) {
  std::vector<NamedArray> arrays;
  try {
    arrays = decode_arrays(bytes);
  } catch (const Error& e) {
    throw Error(networks.string() + ": " + e.what());
  }
  const ArrayTable t(std::move(arrays), networks.string());
  if (t.text("format") != kRuntimeFormat) t.fail("format '" + t.text("format") + "', expected '" + kRuntimeFormat + "'");
  auto s = std::make_unique<Skill::Impl>();
  s->frame_size = t.count("observation.frame_size", 1, kMaxSize);
  s->history = t.count("observation.history", 1, 1024);
  s->action_size = t.count("action_size", 1, kMaxSize);
  if (static_cast<long long>(s->frame_size) * s->history > kMaxSize) t.fail("the policy's input (frame_size x history) is above 2^20 values");
  const int input = s->frame_size * s->history;
  s->layout = parse_layout(t.text("observation.layout"), t);
  int covered = 0;
  for (const ObservationSlice& p : s->layout) {
    if (p.offset != covered) t.fail("array 'observation.layout': part '" + p.name + "' starts at " + std::to_string(p.offset) + ", not " + std::to_string(covered));
    covered += p.size;
  }
  if (covered != s->frame_size)
    t.fail("array 'observation.layout' covers " + std::to_string(covered) + " values of a frame of " + std::to_string(s->frame_size));
  s->bodies = lines_of(t.text("character.bodies"));
  const auto n = static_cast<std::uint32_t>(input);
  const double count = t.scalar("observation.count");
  if (count < 0) t.fail("array 'observation.count' is negative");
  s->normalise = count > 0;
  const std::vector<double>& mean = t.doubles("observation.mean", {n});
  const std::vector<double>& variance = t.doubles("observation.variance", {n});
  const double epsilon = t.scalar("observation.epsilon");
  s->clip = t.scalar("observation.clip");
  if (!(epsilon > 0) || s->clip < 0) t.fail("arrays 'observation.epsilon' and 'observation.clip' must be > 0 and >= 0");
  s->mean = Eigen::Map<const Eigen::VectorXd>(mean.data(), input);
  const Eigen::VectorXd var = Eigen::Map<const Eigen::VectorXd>(variance.data(), input);
  if ((var.array() < 0).any()) t.fail("array 'observation.variance' holds a negative value");
  s->inv_std = (var.array() + epsilon).rsqrt().matrix();  // as RunningNormalizer::normalize
  s->iteration = t.scalar("iteration");
  s->samples = t.scalar("samples");
  s->policy = Network::read(t, "policy.net", input, s->history, activation_of(t, "policy.activation"));
  if (s->policy.output_size() != s->action_size)
    t.fail("the policy's last layer gives " + std::to_string(s->policy.output_size()) + " values for " + std::to_string(s->action_size) + " actions");
  const std::vector<float>& log_std = t.floats("policy.log_std", {static_cast<std::uint32_t>(s->action_size)});
  s->log_std = Eigen::Map<const Eigen::VectorXf>(log_std.data(), s->action_size);
  s->value = Network::read(t, "value.net", input, s->history, activation_of(t, "value.activation"));
  if (s->value.output_size() != 1) t.fail("the value network's last layer gives " + std::to_string(s->value.output_size()) + " values, not 1");
  // Files written before the runtime held discriminators have none.
  const int discriminators = t.has("discriminator.count") ? t.count("discriminator.count", 0, 1024) : 0;
  for (int i = 0; i < discriminators; ++i) s->discriminators.push_back(SkillDiscriminator::read(t, i, s->frame_size, s->action_size));
  return s;
}

FloatMatrix Skill::Impl::normalised(const Eigen::MatrixXd& inputs) const {
  if (inputs.cols() != mean.size())
    throw Error(name + ": a policy input has " + std::to_string(inputs.cols()) + " values, expected " + std::to_string(mean.size()));
  if (!normalise) return inputs.cast<float>();
  Eigen::MatrixXd out = (inputs.rowwise() - mean.transpose()).array().rowwise() * inv_std.transpose().array();
  if (clip > 0) out = out.cwiseMax(-clip).cwiseMin(clip);
  return out.cast<float>();
}

Skill::Skill(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Skill::~Skill() = default;

std::string Skill::default_name(const std::filesystem::path& model_dir) {
  std::filesystem::path full = std::filesystem::absolute(model_dir).lexically_normal();
  if (!full.has_filename()) full = full.parent_path();  // "runs/walk/" names "walk"
  if (full.filename() == "model" && full.has_parent_path() && full.parent_path().has_filename()) return full.parent_path().filename().string();
  return full.filename().string();
}

std::shared_ptr<const Skill> Skill::load(const std::filesystem::path& model_dir, const std::string& name, const std::vector<std::string>& env_settings) {
  const std::filesystem::path config = model_dir / "config.yaml", networks = model_dir / kRuntimeFileName;
  if (!std::filesystem::is_directory(model_dir)) throw Error(model_dir.string() + ": no such model directory");
  if (!std::filesystem::exists(config)) throw Error(config.string() + ": missing (a model directory holds config.yaml and networks.mimic)");
  if (!std::filesystem::exists(networks))
    throw Error(networks.string() + ": missing; `mimic export RUN -o " + model_dir.string() + "` writes it (`--networks-only` beside an existing export)");
  return load_skill(model_dir, read_text_file(networks, kMaxCheckpointBytes), networks, name, env_settings);
}

std::shared_ptr<const Skill> load_skill(const std::filesystem::path& model_dir, std::string_view networks_bytes, const std::filesystem::path& networks,
                                        const std::string& name, const std::vector<std::string>& env_settings) {
  register_control_envs();  // a skill may act in an environment of this layer's (the navigation task)
  const std::filesystem::path config = model_dir / "config.yaml";
  for (const std::string& setting : env_settings)
    if (setting.rfind("env.", 0) != 0) throw Error("setting '" + setting + "': a skill's environment takes env keys only (env.KEY=VALUE)");
  const std::string skill_name = name.empty() ? Skill::default_name(model_dir) : name;
  const YamlReader reader(config.string());
  const YAML::Node root =
      reader.parse(override_config(read_text_file(config, kMaxYamlBytes), config.string(), env_settings), "invalid YAML");
  if (!root.IsMap() || !root["env"].IsDefined()) throw Error(config.string() + ": no 'env' section: the environment the skill acts in");
  // A skill acts on its course as configured: a training curriculum's top level, held
  // (env.terrain.levels, sim/terrain.hpp), in play, videos and every measurement; and it starts
  // from its own clips (other skills' start clips were for training: env.start_clip_share), unless
  // the settings give start clips (a measurement of starts from other motion).
  YAML::Node env = root["env"];
  if (env.IsMap() && env["terrain"].IsMap() && env["terrain"]["levels"].IsDefined()) env["terrain"]["levels"] = 0;
  const bool starts_given = std::any_of(env_settings.begin(), env_settings.end(), [](const std::string& s) {
    return s.rfind("env.start_clips=", 0) == 0 || s.rfind("env.start_clip_share=", 0) == 0;
  });
  if (env.IsMap() && !starts_given) {
    env.remove("start_clips");
    env.remove("start_clip_share");
  }
  return skill_in(make_env_factory(root["env"], reader), networks_bytes, networks, skill_name, model_dir, config.string() + "'s environment",
                  " (a config.yaml that is not the one the networks were exported with?)");
}

std::shared_ptr<const Skill> skill_in(EnvFactory factory, std::string_view networks_bytes, const std::filesystem::path& networks,
                                      const std::string& name, const std::filesystem::path& dir, const std::string& environment,
                                      const std::string& hint) {
  std::unique_ptr<Skill::Impl> s = read_skill_networks(networks_bytes, networks);
  s->dir = dir;
  s->name = name;
  s->factory = std::move(factory);
  // The networks must fit the environment (a config edited after export, or networks copied
  // from another model, would act on the wrong observation).
  const std::unique_ptr<Env> probe = s->factory();
  auto differs = [&](const std::string& what) { throw Error(networks.string() + ": " + what + hint); };
  if (probe->observation_size() != s->frame_size || probe->action_size() != s->action_size)
    differs("the networks take observations of " + std::to_string(s->frame_size) + " values and give " + std::to_string(s->action_size) +
            " actions; " + environment + " has " + std::to_string(probe->observation_size()) + " and " +
            std::to_string(probe->action_size()));
  const std::vector<ObservationSlice> layout = probe->observation_layout();
  bool same_layout = layout.size() == s->layout.size();
  for (std::size_t i = 0; same_layout && i < layout.size(); ++i)
    same_layout = layout[i].name == s->layout[i].name && layout[i].size == s->layout[i].size;
  if (!same_layout) differs("the networks observe " + layout_text(s->layout) + "; " + environment + " " + layout_text(layout));
  const std::vector<std::string> bodies = character_body_names(probe->physics_model());
  if (bodies != s->bodies)
    differs("the networks were trained on a character of " + std::to_string(s->bodies.size()) + " bodies" +
            (s->bodies.empty() ? "" : " (" + s->bodies.front() + " ...)") + "; " + environment + "'s has " + std::to_string(bodies.size()) +
            (bodies.empty() ? "" : " (" + bodies.front() + " ...)"));
  return std::make_shared<const Skill>(std::move(s));
}

std::vector<std::shared_ptr<const Clip>> skill_clips(const Skill& s) {
  const std::unique_ptr<Env> probe = make_skill_env(s);
  CharacterEnv* c = character_of(*probe);
  std::vector<std::shared_ptr<const Clip>> clips;
  if (!c) return clips;
  std::mt19937_64 local(1);
  for (int g = 0; g < std::max(1, c->start_groups()); ++g) {
    if (c->start_groups() > 1) c->choose_start_group(g);
    (void)c->reset(local);
    std::shared_ptr<const Clip> clip = c->start_source().clip;
    if (!clip) clip = c->shared_reference();
    if (clip && std::none_of(clips.begin(), clips.end(), [&](const auto& k) { return k.get() == clip.get(); })) clips.push_back(clip);
  }
  return clips;
}

const std::string& Skill::name() const { return impl_->name; }
const std::filesystem::path& Skill::directory() const { return impl_->dir; }
int Skill::frame_size() const { return impl_->frame_size; }
int Skill::history() const { return impl_->history; }
int Skill::input_size() const { return impl_->frame_size * impl_->history; }
int Skill::action_size() const { return impl_->action_size; }
long long Skill::policy_parameters() const { return impl_->policy.parameters() + impl_->log_std.size(); }

Eigen::MatrixXd Skill::act(const Eigen::MatrixXd& inputs) const { return impl_->policy.forward(impl_->normalised(inputs)).cast<double>(); }

Eigen::VectorXd Skill::act(const Eigen::VectorXd& input) const { return act(Eigen::MatrixXd(input.transpose())).transpose(); }

Eigen::VectorXd Skill::value(const Eigen::MatrixXd& inputs) const { return impl_->value.forward(impl_->normalised(inputs)).col(0).cast<double>(); }

std::vector<std::string> Skill::discriminators() const {
  std::vector<std::string> names;
  for (const SkillDiscriminator& d : impl_->discriminators)
    if (std::find(names.begin(), names.end(), d.source) == names.end()) names.push_back(d.source);
  return names;
}

Eigen::VectorXd Skill::score(const std::string& source, const Eigen::MatrixXd& obs, const Eigen::MatrixXd& next_obs, const Eigen::MatrixXd& actions,
                             int context) const {
  const SkillDiscriminator* found = nullptr;
  int parts = 0;
  for (const SkillDiscriminator& d : impl_->discriminators) {
    if (d.source != source) continue;
    if (d.context < 0) found = &d;
    else if (++parts, d.context == context) found = &d;
  }
  if (parts > 0 && !found)
    throw Error(impl_->name + ": " + source + " has one discriminator per behaviour context: give a context 0 to " + std::to_string(parts - 1));
  if (!found) {
    std::string known;
    for (const std::string& n : discriminators()) known += (known.empty() ? "" : ", ") + n;
    throw Error(impl_->name + ": no discriminator '" + source + "' (" + (known.empty() ? "the skill has none: " + impl_->dir.string() + "/" +
                kRuntimeFileName + " was exported without them, or it learnt from no adversarial reward" : "it has " + known) + ")");
  }
  return found->rewards(obs, next_obs, actions, found->context >= 0 ? -1 : context);
}

std::vector<float> Skill::act_floats(const float* inputs, int batch) const {
  if (batch < 1 || inputs == nullptr) throw Error(impl_->name + ": act_floats needs a batch of at least one input");
  const Eigen::MatrixXd x = Eigen::Map<const FloatMatrix>(inputs, batch, input_size()).cast<double>();
  const FloatMatrix y = impl_->policy.forward(impl_->normalised(x));
  return {y.data(), y.data() + y.size()};
}

}  // namespace mimic
