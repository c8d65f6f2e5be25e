// mimic imitate CLIP... -o RUN: a clip to an evaluated, filmed skill in one command. Puts the clips
// on the character (retargeted with --map where its skeleton is another), records their
// demonstrations into the run, trains with the method's recipe (configs/recipes/), exports the
// model with its clips and demonstrations inside, evaluates it, films it with the clip as a ghost
// and writes report.md with the learning curve. Several clips give one policy that starts from
// all of them (seed 004's integrated multi-clip policy).
#include <spdlog/spdlog.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "app/commands.hpp"
#include "app/eval_file.hpp"
#include "app/evaluate.hpp"
#include "app/policy_video.hpp"
#include "app/recipes.hpp"
#include "app/run_data.hpp"
#include "app/stop_requests.hpp"
#include "core/config_override.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/yaml_reader.hpp"
#include "env/context_env.hpp"
#include "env/env_factory.hpp"
#include "learn/imitation/clip_demonstrations.hpp"
#include "learn/trainer/ranks.hpp"
#include "learn/trainer/run_log.hpp"
#include "learn/trainer/train_config.hpp"
#include "learn/trainer/trainer.hpp"
#include "motion/clip.hpp"
#include "motion/resample.hpp"
#include "motion/retarget.hpp"
#include "motion/retarget_maps.hpp"
#include "render/line_chart.hpp"

namespace mimic::app {

namespace {

namespace fs = std::filesystem;

constexpr const char* kDefaultCharacter = "deepmimic/characters/humanoid3d.txt";  // the recipes' (under the shared data)
constexpr double kGetUpFallenStarts = 0.1;  // the share of a get-up's episodes that start fallen (ASE drops 10 %)
constexpr int kDemonstrationPasses = 8;  // passes over each clip, offset by a fraction of a control step
// The shortest evaluation episode: a run that trained on shorter ones (the tracking recipe's 2 s) is
// judged over this long (a cyclic clip's trials run to it; a non-cyclic clip's end at the clip's end).
constexpr double kEvalSeconds = 20.0;

struct ImitateArgs {
  std::vector<fs::path> clips;
  fs::path out, map, from;
  std::string method = "iccgan";
  std::string task = "none";  // "heading": steering (task_settings)
  LoadOptions load;  // load.character: the character (default: the recipe's humanoid)
  std::vector<std::string> start_clips;  // --start-clips: other skills' motion (CLIP or CLIP@FROM[:TO]) to start a share of episodes from
  std::vector<std::string> settings;  // --set KEY.PATH=VALUE over the recipe, recorded in the run's config
  long long samples = 0;  // 0: the recipe's budget (a resumed run: its own)
  std::uint64_t seed = 1;
  int threads = -1, trials = 10;
  double video_seconds = 10.0;
  bool resume = false;
};

// "1h02m", "3m05s", "12s".
std::string duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "-";
  const long s = std::lround(seconds);
  if (s >= 3600) return fmt::format("{}h{:02}m", s / 3600, (s % 3600) / 60);
  if (s >= 60) return fmt::format("{}m{:02}s", s / 60, s % 60);
  return fmt::format("{}s", s);
}

// Iterations of `per_iteration` samples that cover `samples` (at least one).
int iterations_for(long long samples, long long per_iteration) {
  return static_cast<int>(std::max(1LL, (samples + per_iteration - 1) / per_iteration));
}

// The command line that makes this run, for its report.
std::string command_line(const ImitateArgs& a) {
  std::string line = "mimic imitate";
  for (const fs::path& c : a.clips) line += " " + c.string();
  line += " -o " + a.out.string() + " --method " + a.method;
  if (!a.load.character.empty()) line += " --character " + a.load.character.string();
  if (!a.map.empty()) line += " --map " + a.map.string();
  if (!a.from.empty()) line += " --from " + a.from.string();
  if (a.samples > 0) line += fmt::format(" --samples {}", a.samples);
  if (a.seed != 1) line += fmt::format(" --seed {}", a.seed);
  if (a.task != "none") line += " --task " + a.task;
  if (!a.start_clips.empty()) {
    line += " --start-clips";
    for (const std::string& c : a.start_clips) line += " " + c;
  }
  for (const std::string& setting : a.settings) line += " --set " + setting;
  return line;
}

// The clips on the character, checked to fit it, retargeted first where a map is given (a file or
// a built-in map's name). Without one, a clip that does not fit is retargeted by the one built-in
// map that fits its skeleton onto the character's. Nothing is written here: bad input fails
// before the run directory exists.
std::vector<Clip> clips_on_character(const ImitateArgs& a, const std::vector<fs::path>& paths, const fs::path& character) {
  LoadOptions load = a.load;
  load.character = character;
  const std::optional<RetargetMap> given = a.map.empty() ? std::nullopt : std::optional<RetargetMap>(load_retarget_map_or_builtin(a.map.string()));
  const fs::path ctrl = character.parent_path() / (character.stem().string() + "_ctrl.txt");
  std::optional<Skeleton> target;
  const auto target_skeleton = [&]() -> const Skeleton& {
    if (!target) target = CharacterModel::from_deepmimic(character, fs::exists(ctrl) ? ctrl : fs::path{}).skeleton;
    return *target;
  };
  std::vector<Clip> clips;
  for (const fs::path& path : paths) {
    Clip clip = load_motion(path, given ? a.load : load);
    std::optional<RetargetMap> map = given;
    if (!map) try {
        (void)character_for(clip, path, load);
      } catch (const Error& unfit) {
        try {
          map = fitting_builtin_map(clip, path, target_skeleton(), character);
        } catch (const Error& none) {
          throw Error(std::string(unfit.what()) + "; " + none.what());
        }
      }
    if (map) {
      RetargetReport report;
      const std::string name = clip.name;
      clip = retarget(clip, target_skeleton(), *map, &report);
      clip.name = name;
      spdlog::info("retargeted {} by {}:\n{}", path.string(), map->source, retarget_summary(report));
      (void)character_for(clip, path, load);
    }
    for (const Clip& other : clips)
      if (other.name == clip.name) clip.name += fmt::format("_{}", clips.size() + 1);
    clips.push_back(std::move(clip));
  }
  return clips;
}

// --start-clips' arguments: a file, or a stretch of one (FILE@FROM[:TO]). An existing file is
// taken whole, whatever its name holds.
std::vector<ClipStretch> start_clip_stretches(const std::vector<std::string>& texts) {
  std::vector<ClipStretch> out;
  for (const std::string& text : texts) {
    if (fs::is_regular_file(text)) {
      out.push_back(ClipStretch{text});
      continue;
    }
    try {
      out.push_back(parse_clip_stretch(text));
    } catch (const Error& e) {
      throw Error(std::string("--start-clips ") + e.what());
    }
    if (!fs::is_regular_file(out.back().file)) throw Error("--start-clips " + text + ": no file " + out.back().file);
  }
  return out;
}

// Clips named alike (two stretches of one clip, or two files of one name) are kept apart in the
// run's files: the second of a name becomes NAME_2, the third NAME_3, and so on.
void distinct_names(std::vector<Clip>& clips) {
  std::vector<std::string> taken;
  for (Clip& c : clips) {
    std::string name = c.name;
    for (int k = 2; std::find(taken.begin(), taken.end(), name) != taken.end(); ++k) name = c.name + "_" + std::to_string(k);
    c.name = name;
    taken.push_back(name);
  }
}

// The recipe's changes for --task heading (seed 004 eq. 8's goal mixing, docs/imitate.md): the
// environment draws a target heading every 4 s within 90 degrees of where the character faces,
// the policy observes it, and the reward is 0.5 of the goal term plus 0.5 of the recipe's
// discriminator. From a trained skill (--from) the exploration noise is held at sigma = e^-1.66
// (0.19 rad): a trained skill's own noise is too small to find the turns a new goal asks for.
std::vector<std::string> task_settings(const ImitateArgs& a) {
  if (a.task == "none") return {};
  std::vector<std::string> s{"env.goal=heading", "env.goal_turn=90", "env.alive_bonus=0", "env.control_weight=0", "rewards.0.weight=0.5",
                             "rewards.1={source: env, weight: 0.5}"};
  if (!a.from.empty()) {
    s.emplace_back("policy.learn_std=false");
    s.emplace_back("policy.log_std=-1.66");
  }
  return s;
}

// The environment keys imitate fills in for every run (the clips, the character, the task's, and the
// clips' own contacts, which follow the clip), whatever a --from model was trained with.
const std::vector<std::string>& imitate_filled_env_keys() {
  static const std::vector<std::string> filled{"name",      "character",           "clip",          "start_clips",
                                               "start_clip_share", "fallen_starts", "goal",        "goal_turn",
                                               "alive_bonus",      "control_weight", "allow_clip_contacts"};
  return filled;
}

// The fine-tune of a --from model acts in the environment the model was trained in: "env.KEY=VALUE"
// for each key the model's config sets otherwise than the recipe (but the filled ones), applied
// before the user's own --set, which wins. A recipe's PD limit, drift limit or start momentum other
// than the model's changes what its actions do (a run trained with `pd_limit: total` fine-tuned
// without it fell in 9 of 20 trials). Empty where the model's config cannot be read (training
// then says why).
std::vector<std::string> model_env_settings(const fs::path& model, const std::string& recipe_text) {
  YAML::Node theirs, recipe;
  try {
    theirs = YAML::Load(read_text_file(model / "config.yaml"))["env"];
    recipe = YAML::Load(recipe_text)["env"];
  } catch (const std::exception&) {
    return {};
  }
  if (!theirs.IsMap()) return {};
  const std::vector<std::string>& filled = imitate_filled_env_keys();
  std::vector<std::string> out;
  for (const auto& kv : theirs) {
    const std::string key = kv.first.Scalar(), value = flow_yaml(kv.second);
    if (std::find(filled.begin(), filled.end(), key) != filled.end()) continue;
    if (recipe.IsMap() && recipe[key] && flow_yaml(recipe[key]) == value) continue;  // the recipe's already
    out.push_back("env." + key + "=" + value);
  }
  return out;
}

// The environment keys a --from model was trained with that the new run still sets otherwise after
// model_env_settings (those the user --set, and those the model leaves unset), aside from those
// imitate fills in for every run: what a fine-tune changes under the model, as "max_seconds: 2 in
// the model, 3 in the run". Empty where they agree or the model's config cannot be read.
std::string env_keys_changed(const fs::path& model, const std::string& run_text) {
  const std::vector<std::string>& filled = imitate_filled_env_keys();
  YAML::Node theirs, ours;
  try {
    theirs = YAML::Load(read_text_file(model / "config.yaml"))["env"];
    ours = YAML::Load(run_text)["env"];
  } catch (const std::exception&) {
    return "";
  }
  if (!theirs.IsMap() || !ours.IsMap()) return "";
  auto text = [](const YAML::Node& n) { return n ? flow_yaml(n) : std::string("unset"); };
  std::vector<std::string> keys;
  for (const YAML::Node* side : {&theirs, &ours})
    for (const auto& kv : *side)
      if (std::find(keys.begin(), keys.end(), kv.first.Scalar()) == keys.end()) keys.push_back(kv.first.Scalar());
  std::string out;
  for (const std::string& k : keys) {
    if (std::find(filled.begin(), filled.end(), k) != filled.end()) continue;
    const YAML::Node a = theirs[k], b = ours[k];
    if (a && b && config_difference(flow_yaml(a), "the model", flow_yaml(b), "the run").empty()) continue;
    out += (out.empty() ? "" : "; ") + k + ": " + text(a) + " in the model, " + text(b) + " in the run";
  }
  return out;
}

// A new run: clips (and a given character) copied in, the recipe's config with them, the clips'
// demonstrations.
void start_run(const ImitateArgs& a, const Recipe& recipe) {
  if (a.clips.empty()) throw Error("imitate: give one clip or more (or --resume -o RUN to go on with a run)");
  if (fs::exists(a.out) && !(fs::is_directory(a.out) && fs::is_empty(a.out)))
    throw Error(a.out.string() + " already exists: `mimic imitate --resume -o " + a.out.string() + "` goes on with it; or choose another -o");
  if (!a.start_clips.empty() && a.method == "tracking")
    throw Error("--start-clips starts episodes away from the clip a tracking policy follows: use --method iccgan or gail");
  if (a.task != "none" && a.method == "tracking")
    throw Error("--task " + a.task + " mixes its goal with an adversarial reward: use --method iccgan or gail, not tracking");
  if (a.method == "tracking" && a.clips.size() != 1)
    throw Error("--method tracking follows one clip; give one (iccgan and gail learn one policy from several)");
  fs::path character = a.load.character;
  if (character.empty()) {
    const fs::path shared = shared_data_dir();
    if (shared.empty() || !fs::exists(shared / kDefaultCharacter))
      throw Error(std::string("the recipes' character is DeepMimic's humanoid, ") + kDefaultCharacter +
                  " under the shared data directory, which is absent (set MIMIC_DATA); or give --character FILE");
    character = shared / kDefaultCharacter;
  } else if (!fs::is_regular_file(character)) {
    throw Error("--character " + character.string() + ": not found");
  }
  std::vector<Clip> clips = clips_on_character(a, a.clips, character);
  distinct_names(clips);
  std::vector<Clip> start_clips;
  {
    const std::vector<ClipStretch> stretches = start_clip_stretches(a.start_clips);
    std::vector<fs::path> files;
    for (const ClipStretch& s : stretches) files.emplace_back(s.file);
    start_clips = clips_on_character(a, files, character);
    for (std::size_t i = 0; i < start_clips.size(); ++i) start_clips[i] = cut(start_clips[i], stretches[i]);
    distinct_names(start_clips);
  }
  const std::string recipe_source = "configs/recipes/" + a.method + ".yaml";
  std::vector<std::string> own = task_settings(a);
  own.insert(own.end(), a.settings.begin(), a.settings.end());
  const TrainConfig recipe_cfg = parse_train_config(override_config(recipe.text, recipe_source, own), recipe_source);
  const long long per_iteration = recipe_cfg.collect.samples * ranks::size();  // every rank's (mpirun)
  // The recipe's budget in samples, however many ranks share it.
  const long long samples = a.samples > 0 ? a.samples : static_cast<long long>(recipe_cfg.collect.samples) * recipe_cfg.iterations;
  std::vector<std::string> settings{fmt::format("iterations={}", iterations_for(samples, per_iteration)),
                                    fmt::format("seed={}", a.seed)};
  if (a.threads >= 0) settings.push_back(fmt::format("collect.threads={}", resolve_threads(a.threads)));
  std::string clip_list;
  for (const Clip& c : clips) clip_list += (clip_list.empty() ? "" : ", ") + json_string("clips/" + c.name + ".mclip");
  // One clip is the environment's reference (what eval and the video's ghost compare with).
  settings.push_back(clips.size() == 1 ? "env.clip=" + clip_list : "env.clip=[" + clip_list + "]");
  if (!start_clips.empty()) {
    std::string start_list;
    for (const Clip& c : start_clips) start_list += (start_list.empty() ? "" : ", ") + json_string("start_clips/" + c.name + ".mclip");
    settings.push_back("env.start_clips=[" + start_list + "]");
  }
  if (!a.load.character.empty()) settings.push_back("env.character=" + json_string("character/" + character.filename().string()));
  // A get-up (clips that begin lying) learns to get up from how characters land too: recovery hands
  // it a character pushed over, in poses its clips never show (docs/imitate.md).
  if (a.method != "tracking" && std::any_of(clips.begin(), clips.end(), [](const Clip& c) { return begins_lying(c); }))
    settings.push_back(fmt::format("env.fallen_starts={}", kGetUpFallenStarts));
  const std::vector<std::string> kept = a.from.empty() ? std::vector<std::string>{} : model_env_settings(a.from, recipe.text);
  settings.insert(settings.end(), kept.begin(), kept.end());
  settings.insert(settings.end(), own.begin(), own.end());  // the task's, then the user's last: they win

  // Everything is known to fit: write the run (and take it away again if that fails: it was new).
  try {
    fs::create_directories(a.out / "clips");
    for (const Clip& c : clips) save_clip(c, a.out / "clips" / (c.name + ".mclip"));
    if (!start_clips.empty()) fs::create_directories(a.out / "start_clips");
    for (const Clip& c : start_clips) save_clip(c, a.out / "start_clips" / (c.name + ".mclip"));
    if (!a.load.character.empty()) {
      fs::create_directories(a.out / "character");
      fs::copy_file(character, a.out / "character" / character.filename());
      const fs::path ctrl = character.parent_path() / (character.stem().string() + "_ctrl.txt");
      if (fs::exists(ctrl)) fs::copy_file(ctrl, a.out / "character" / ctrl.filename());
    }
    const std::string text = "# " + command_line(a) + "\n# the recipe configs/recipes/" + a.method + ".yaml with the clips filled in\n" +
                             override_config(recipe.text, recipe_source, settings);
    const fs::path config = a.out / "config.yaml";
    write_file_atomic(config, text);
    spdlog::info("{}: {} clip{} on {}, recipe {}", a.out.string(), clips.size(), clips.size() == 1 ? "" : "s", character.string(), a.method);
    if (!kept.empty())
      spdlog::info("{}: the fine-tune acts in the environment {} was trained in (its env keys kept; --set env.KEY=VALUE sets one otherwise)",
                   a.out.string(), a.from.string());
    if (!a.from.empty())
      if (const std::string changed = env_keys_changed(a.from, text); !changed.empty())
        spdlog::warn("{} was trained in another environment than this run's ({}): the fine-tune trains in the run's",
                     a.from.string(), changed);
    if (a.method == "tracking") return;
    const TrainConfig cfg = parse_train_config(text, config.string());
    const std::unique_ptr<Env> env = make_env_factory(cfg.env, YamlReader(cfg.source))();
    auto* character_env = dynamic_cast<CharacterEnv*>(env.get());
    if (!character_env) throw Error(config.string() + ": the recipe's environment has no character to pose from the clips");
    const Demonstrations d = clip_demonstrations(*character_env, clips, kDemonstrationPasses);
    write_demonstrations(a.out / "demos.csv", d);
    spdlog::info("recorded {}: {} transitions of the clips ({} passes each), the discriminator's examples", (a.out / "demos.csv").string(),
                 d.size(), kDemonstrationPasses);
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(a.out, ignored);
    throw;
  }
}

// Trains to the run's iteration count; false when a stop request ended it first.
bool train(const ImitateArgs& a) {
  const fs::path config = a.out / "config.yaml";
  TrainConfig cfg = parse_train_config(read_text_file(config), config.string());
  const long long per_iteration = static_cast<long long>(cfg.collect.samples) * ranks::size();  // every rank's (mpirun)
  if (a.resume && a.samples > 0) cfg.iterations = iterations_for(a.samples, per_iteration);
  if (a.resume && a.threads >= 0) cfg.collect.threads = resolve_threads(a.threads);
  TrainOptions opts;
  opts.run_dir = a.out;
  opts.resume = a.resume;
  opts.init_from = a.from;
  opts.stop_requests = stop_requests;
  const auto start = std::chrono::steady_clock::now();
  double first_samples = -1;
  const long long total = cfg.iterations * per_iteration;
  opts.on_iteration = [&, total, per_iteration](const IterationMetrics& m) {
    const double samples = m.get("samples"), elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (first_samples < 0) first_samples = samples - static_cast<double>(per_iteration);
    const double rate = (samples - first_samples) / std::max(elapsed, 1e-9);
    const double episode_return = m.get("return");  // of the episodes that ended in the iteration: NaN where none did
    spdlog::info("iter {:>5}/{}  samples {:>10.0f} ({:4.1f} %)  reward {:6.3f}  return {:>8}  elapsed {}  ETA {}", m.iteration,
                 cfg.iterations, samples, 100.0 * samples / static_cast<double>(total), m.get("reward"),
                 std::isfinite(episode_return) ? fmt::format("{:.2f}", episode_return) : "-", duration(m.get("wall_s")),
                 duration((static_cast<double>(total) - samples) / rate));
  };
  handle_stop_signals();
  Trainer trainer(cfg, opts);
  spdlog::info("{} {}: {} iterations of {} samples ({} envs, {} threads)", a.resume ? "resuming" : "training", a.out.string(),
               cfg.iterations, cfg.collect.samples, cfg.collect.envs, cfg.collect.threads);
  const RunEnd end = trainer.run();
  if (end.stopped)
    spdlog::info("stopped at iteration {} ({} samples), saved; `mimic imitate --resume -o {}` goes on from it", end.iteration,
                 trainer.samples(), a.out.string());
  return !end.stopped;
}

// RUN/model: the acting-only export, with the clips, demonstrations and character it names, so
// that it loads wherever it is copied. Replaces an earlier one only once it is written.
fs::path export_model(const fs::path& run) {
  const fs::path model = run / "model", fresh = run / "model.new";
  fs::remove_all(fresh);
  const std::unique_ptr<Trainer> trainer = Trainer::from_run(run, /*reward_sources=*/true);
  fs::create_directories(fresh);
  copy_run_data(run, fresh);
  for (const char* own : {"config.yaml", "metrics.csv"})
    if (fs::exists(run / own)) fs::copy(run / own, fresh / own);
  trainer->export_model(fresh / "checkpoint.pt");
  fs::remove_all(model);
  fs::rename(fresh, model);
  spdlog::info("exported {} (iteration {}, {} samples)", model.string(), trainer->iteration(), trainer->samples());
  return model;
}

void write_curves(const fs::path& run) {
  const MetricsTable t = read_metrics_csv(run / "metrics.csv");
  LineChart chart;
  chart.title = "Learning curve: imitation reward per step";
  chart.x_label = "samples";
  chart.y_label = "reward per step";
  chart.series.push_back({run.filename().string(), t.column("samples"), t.column("reward")});
  write_line_chart(run / "curves.png", chart);
}

// The run's clips, sorted by name.
std::vector<fs::path> clips_of(const fs::path& dir) {
  std::vector<fs::path> clips;
  for (const auto& entry : fs::directory_iterator(dir / "clips")) clips.push_back(entry.path());
  std::sort(clips.begin(), clips.end());
  return clips;
}

// The env overrides the model is evaluated with: episodes of kEvalSeconds where its config's
// max_seconds is shorter; none otherwise.
std::vector<std::string> eval_settings(const fs::path& model) {
  const YAML::Node env = model_env_section(model).env;
  const YAML::Node seconds = env.IsMap() ? env["max_seconds"] : YAML::Node();
  if (seconds && seconds.IsScalar() && seconds.as<double>() < kEvalSeconds) return {fmt::format("env.max_seconds={}", kEvalSeconds)};
  return {};
}

// The evaluation file of each clip: eval.json for one, eval_<clip>.json for several.
fs::path eval_file(const fs::path& run, const fs::path& clip, std::size_t clips) {
  return clips == 1 ? run / "eval.json" : run / ("eval_" + clip.stem().string() + ".json");
}

// `overrides`: the env settings it was evaluated and filmed with (eval_settings); `processes`: how
// many ranks trained it (mpirun).
void write_report(const ImitateArgs& a, const std::vector<std::string>& overrides, bool video, int processes) {
  const MetricsTable t = read_metrics_csv(a.out / "metrics.csv");
  const std::string config_text = read_text_file(a.out / "config.yaml");
  const TrainConfig cfg = parse_train_config(config_text, (a.out / "config.yaml").string());
  // The run's own method and command (a resumed run's arguments name neither): its rewards say
  // which recipe it is, and start_run wrote the command as the config's first line.
  const std::string method = !cfg.rewards.empty() && cfg.rewards[0].source != "env" ? cfg.rewards[0].source : "tracking";
  std::string made_by = config_text.rfind("# mimic imitate ", 0) == 0 ? config_text.substr(2, config_text.find('\n') - 2) : command_line(a);
  if (a.resume) made_by += "`, then `mimic imitate --resume -o " + a.out.string();
  const double samples = t.column("samples").back(), wall = t.column("wall_s").back();
  const std::vector<fs::path> clips = clips_of(a.out);
  std::string names;
  for (const fs::path& c : clips) names += (names.empty() ? "" : ", ") + c.stem().string();
  std::string text = fmt::format("# {}: {} imitation of {}\n\n", a.out.filename().string(), method, names);
  text += fmt::format("Made by `{}`: the recipe configs/recipes/{}.yaml (the run's config.yaml is it with the clips filled in).\n\n",
                      made_by, method);
  text += "| | |\n|---|---|\n";
  text += fmt::format("| samples | {:.0f} ({} iteration{} of {}) |\n", samples, t.rows.size(), t.rows.size() == 1 ? "" : "s",
                      processes > 1 ? fmt::format("{} on each of {} ranks", cfg.collect.samples, processes) : std::to_string(cfg.collect.samples));
  // A run resumed with another --threads than it started with says both (the config keeps the first).
  const int resumed_threads = a.resume && a.threads >= 0 ? resolve_threads(a.threads) : cfg.collect.threads;
  std::string threads = fmt::format("{} thread{}{}", cfg.collect.threads, cfg.collect.threads == 1 ? "" : "s", processes > 1 ? " a rank" : "");
  if (resumed_threads != cfg.collect.threads) threads = fmt::format("started with {}, last resumed with {}", threads, resumed_threads);
  text += fmt::format("| wall time | {} ({}) |\n", duration(wall), threads);
  for (const fs::path& clip : clips) {
    const EvalSummary e = read_eval_json(eval_file(a.out, clip, clips.size()));
    const std::string of = clips.size() == 1 ? "" : " (" + clip.stem().string() + ")";
    if (std::isfinite(e.error_mean))
      text += fmt::format("| imitation error{} | {:.3f} ± {:.3f} m (mean over links of the world position error; {} trials from evenly "
                          "spaced phases of the clip) |\n",
                          of, e.error_mean, e.error_std, e.trials);
    if (e.down >= 0) text += fmt::format("| down{} | {} of {} trials (a fall, or lying 10 frames) |\n", of, e.down, e.trials);
    if (std::isfinite(e.progress)) text += fmt::format("| progress{} | {:.2f} of the clip's ground covered |\n", of, e.progress);
    if (clip == clips.front()) text += fmt::format("| episode length | {:.0f} steps (mean actions) |\n", e.episode_length);
  }
  text += "\n![learning curve](curves.png)\n\n";
  if (video) text += "Video: [video.mp4](video.mp4) (the translucent ghost is the clip).\n\n";
  std::string eval_sets;
  for (const std::string& setting : overrides) eval_sets += " --set " + setting;
  if (!eval_sets.empty())
    text += fmt::format("{} on episodes of {:.0f} s (`{}`), longer than those it trained on.\n\n", video ? "Evaluated and filmed" : "Evaluated",
                        kEvalSeconds, eval_sets.substr(1));
  text += "The model is `model/` (its clips and demonstrations inside): `mimic eval " + (a.out / "model").string() + eval_sets +
          "`, `mimic render " + (a.out / "model").string() + " -o skill.mp4 --ghost" + eval_sets + "`, or load it from a program with the runtime " +
          "(docs/runtime.md). The evaluation files hold the figures above.\n";
  write_file_atomic(a.out / "report.md", text);
}

void imitate(const ImitateArgs& a) {
  if (a.resume && !a.from.empty()) throw Error("--from starts a new run; a resumed run goes on from its own weights");
  if (a.resume && !a.settings.empty()) throw Error("--set: a resumed run keeps the config it was started with");
  if (a.resume && a.task != "none") throw Error("--task: a resumed run keeps the task it was started with");
  if (a.resume) {
    if (!a.clips.empty()) throw Error("--resume goes on with the run's own clips: give none");
    if (!fs::exists(a.out / "config.yaml") || !fs::exists(a.out / "checkpoint.pt"))
      throw Error(a.out.string() + ": no run to resume (config.yaml and checkpoint.pt); start one without --resume");
  } else if (ranks::rank() == 0) {
    start_run(a, recipe(a.method));  // (over several ranks, rank 0 writes the run; the others train in it)
  }
  ranks::barrier();
  bool finished = false;
  try {
    finished = train(a);
  } catch (...) {
    // A new run that failed before its first checkpoint cannot be resumed: leave nothing of it.
    std::error_code ignored;
    if (!a.resume && ranks::rank() == 0 && !fs::exists(a.out / "checkpoint.pt")) fs::remove_all(a.out, ignored);
    throw;
  }
  // The model, its evaluation, video and report are rank 0's to make, alone.
  if (!finished || ranks::rank() > 0) return;
  // Training is done; what follows is quick to make again: Ctrl-C ends it at once.
  release_stop_signals();
  const int trained_by = ranks::size();
  ranks::continue_alone();
  const fs::path model = export_model(a.out);
  // Against each clip: eval.json for one, eval_<clip>.json for several.
  const std::vector<fs::path> clips = clips_of(model);
  const std::vector<std::string> settings = eval_settings(model);  // evaluated, filmed and reported alike
  for (const fs::path& clip : clips) {
    EvalArgs e;
    // The clip named: an imitation environment draws starts from its clips but tracks none.
    e.run = model, e.episodes = a.trials, e.trials = a.trials, e.json = eval_file(a.out, clip, clips.size()), e.clip = clip;
    e.settings = settings;
    evaluate(e);
  }
  bool video = false;
  if (a.video_seconds > 0) {
    PolicyVideoOptions o;
    o.width = 480, o.height = 360, o.seconds = a.video_seconds, o.ghost = true;
    o.env_settings = settings;  // a run trained on short episodes is filmed without restarts
    try {
      const PolicyVideoStats s = render_policy_video(model, a.out / "video.mp4", o);
      spdlog::info("filmed {} ({} frames; the translucent ghost is the clip)", (a.out / "video.mp4").string(), s.frames);
      video = true;
    } catch (const Error& err) {
      spdlog::warn("no video: {}", err.what());
    }
  }
  write_curves(a.out);
  write_report(a, settings, video, trained_by);
  spdlog::info("wrote {}: the model, its evaluation, {}curves.png and report.md", a.out.string(), video ? "video.mp4, " : "");
}

}  // namespace

void add_imitate_command(CLI::App& app) {
  auto args = std::make_shared<ImitateArgs>();
  CLI::App* cmd = app.add_subcommand("imitate", "a clip to a trained, evaluated and filmed skill in one command (docs/imitate.md)");
  cmd->add_option("clips", args->clips, "motion clips (.mclip, .bvh, .amc, DeepMimic .txt); several train one policy from all")
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--out", args->out, "run directory to write (the model, eval.json, video.mp4, report.md end up in it)")->required();
  CLI::Option* method = cmd->add_option("--method", args->method, "iccgan (seed 004's discriminator ensemble), gail (seed 000) or tracking (seed 003)")
      ->capture_default_str()
      ->check(CLI::IsMember({"iccgan", "gail", "tracking"}));
  cmd->add_option("--map", args->map,
                  "retarget map for clips whose skeleton is not the character's: a YAML file (docs/retargeting.md) or a built-in map's "
                  "name (" + builtin_retarget_map_list() + "); without it, the one built-in map that fits such a clip");
  cmd->add_option("--from", args->from, "start from a trained skill's weights (a model or run directory), e.g. a shipped walk")
      ->check(CLI::ExistingPath);
  cmd->add_option("--task", args->task, "none, or heading: steering, a target direction the skill walks towards (seed 004 eq. 8)")
      ->capture_default_str()
      ->check(CLI::IsMember({"none", "heading"}));
  CLI::Option* start_clips = cmd->add_option(
      "--start-clips", args->start_clips,
      "other skills' clips: three quarters of the episodes start from them (env.start_clip_share), so that the skill can take over from those "
      "skills; CLIP@FROM[:TO] a stretch of one in seconds, negative from its end (getup.txt@-0.3: where a get-up hands over)");
  cmd->add_option("--samples", args->samples, "training budget in samples (default: the recipe's, 2e7 as seed 004)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--seed", args->seed, "random seed")->capture_default_str();
  cmd->add_option("--threads", args->threads, "collection threads (0: every core; default: the recipe's)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--trials", args->trials, "evaluation episodes and imitation trials")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--video-seconds", args->video_seconds, "length of the video (0: none)")->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--set", args->settings,
                  "override a value of the recipe: KEY.PATH=VALUE (e.g. env.max_seconds=20, collect.envs=8); repeatable; recorded in the "
                  "run's config");
  cmd->add_flag("--resume", args->resume, "go on with the run in -o (after a stop, or with a larger --samples)")
      ->excludes(method)
      ->excludes(start_clips);  // a resumed run keeps its own recipe and start clips
  add_load_options(*cmd, args->load);
  cmd->callback([args] { imitate(*args); });
}

}  // namespace mimic::app
