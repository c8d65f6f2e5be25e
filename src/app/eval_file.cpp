#include "app/eval_file.hpp"

#include <cmath>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/yaml_reader.hpp"

namespace mimic::app {

namespace {

double number_or_nan(const YamlReader& r, const YAML::Node& map, const char* key, const std::string& where) {
  const YAML::Node n = map[key];
  if (!n || n.IsNull()) return NAN;
  return r.number(n, where + " \"" + key + "\"");
}

}  // namespace

EvalSummary read_eval_json(const std::filesystem::path& path) {
  const YamlReader r(path.string(), '"');
  const YAML::Node root = r.parse(read_text_file(path), path.string() + ": not an evaluation file (JSON from mimic eval --json)");
  if (!root.IsMap()) throw Error(path.string() + ": not an evaluation file (JSON from mimic eval --json)");
  EvalSummary s;
  s.run = r.text(r.member(root, "run", "the evaluation"), "\"run\"");
  s.return_mean = number_or_nan(r, root, "return_mean", "the evaluation");
  s.episode_length = number_or_nan(r, root, "episode_length", "the evaluation");
  if (const YAML::Node im = root["imitation"]) {
    s.clip = r.text(r.member(im, "clip", "\"imitation\""), "\"imitation\" \"clip\"");
    s.error_mean = number_or_nan(r, im, "error_mean", "\"imitation\"");
    s.error_std = number_or_nan(r, im, "error_std", "\"imitation\"");
    s.normalised_return = number_or_nan(r, im, "normalised_return", "\"imitation\"");
    s.progress = number_or_nan(r, im, "progress", "\"imitation\"");  // null for a clip that stays put
    s.falls = r.integer(r.member(im, "falls", "\"imitation\""), "\"imitation\" \"falls\"");
    if (const YAML::Node d = im["down"]) s.down = r.integer(d, "\"imitation\" \"down\"");  // older files have none
    s.trials = r.integer(r.member(im, "trials", "\"imitation\""), "\"imitation\" \"trials\"");
  }
  if (const YAML::Node rob = root["robustness"]) {
    if (!rob.IsSequence()) r.fail(rob, "\"robustness\": expected a list");
    for (const YAML::Node& p : rob) {
      s.masses.push_back(r.number(r.member(p, "mass", "a robustness point"), "\"mass\""));
      s.frames.push_back(r.number(r.member(p, "frames_mean", "a robustness point"), "\"frames_mean\""));
      s.frames_std.push_back(number_or_nan(r, p, "frames_std", "a robustness point"));
      s.max_frames.push_back(number_or_nan(r, p, "max_frames", "a robustness point"));
    }
  }
  if (const YAML::Node tr = root["transitions"]) {
    const YAML::Node cells = r.member(tr, "cells", "\"transitions\"");
    if (!cells.IsSequence()) r.fail(cells, "\"transitions\" \"cells\": expected a list");
    for (const YAML::Node& c : cells) {
      EvalSummary::Transition t;
      t.from = r.text(r.member(c, "from", "a transition cell"), "\"from\"");
      t.to = r.text(r.member(c, "to", "a transition cell"), "\"to\"");
      t.rule = r.text(r.member(c, "rule", "a transition cell"), "\"rule\"");
      t.threshold = number_or_nan(r, c, "threshold", "a transition cell");
      t.success_rate = r.number(r.member(c, "success_rate", "a transition cell"), "\"success_rate\"");
      t.mean_wait = number_or_nan(r, c, "mean_wait", "a transition cell");
      s.transitions.push_back(std::move(t));
    }
  }
  if (const YAML::Node rec = root["recovery"]) {
    const YAML::Node masses = r.member(rec, "masses", "\"recovery\"");
    if (!masses.IsSequence()) r.fail(masses, "\"recovery\" \"masses\": expected a list");
    for (const YAML::Node& m : masses) {
      EvalSummary::Recovery p;
      p.mass = r.number(r.member(m, "mass", "a recovery point"), "\"mass\"");
      const YAML::Node without = r.member(m, "without", "a recovery point"), with = r.member(m, "with", "a recovery point");
      p.without = r.number(r.member(without, "performing_mean", "\"without\""), "\"performing_mean\"");
      p.without_std = number_or_nan(r, without, "performing_std", "\"without\"");
      p.with = r.number(r.member(with, "performing_mean", "\"with\""), "\"performing_mean\"");
      p.with_std = number_or_nan(r, with, "performing_std", "\"with\"");
      s.recovery.push_back(p);
    }
  }
  return s;
}

}  // namespace mimic::app
