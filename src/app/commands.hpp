#pragma once
// Sub-commands of the `mimic` command line, one registration function per group.
#include <CLI/CLI.hpp>

#include "motion/clip_io.hpp"
#include "motion/retarget.hpp"
#include "sim/character_model.hpp"

namespace mimic::app {

void add_motion_commands(CLI::App& app);
void add_demo_command(CLI::App& app);
void add_render_commands(CLI::App& app);
void add_character_scale_command(CLI::App& app);  // under `mimic character` (add_render_commands)
void add_train_commands(CLI::App& app);
void add_imitation_commands(CLI::App& app);
void add_imitate_command(CLI::App& app);
void add_distill_command(CLI::App& app);
void add_eval_command(CLI::App& app);
void add_play_command(CLI::App& app);
void add_report_commands(CLI::App& app);
void add_video_commands(CLI::App& app);
void add_reconstruct_command(CLI::App& app);
void add_complete_command(CLI::App& app);
void add_bench_policy_command(CLI::App& bench);  // under `mimic bench`

// Options every command that reads a motion file accepts.
void add_load_options(CLI::App& cmd, LoadOptions& opts);

// A character's skeleton: a DeepMimic character file, or the skeleton of a .mclip.
Skeleton load_target_skeleton(const std::filesystem::path& path);

// A human-readable summary of a clip (several lines).
std::string clip_summary(const Clip& clip);

// The character to play a clip on: --character (DeepMimic), else the DeepMimic character named
// like the clip (a .txt) or of the shared data whose skeleton an .mclip is on, else a simple body
// built on the clip's own skeleton. Throws if they do not fit.
CharacterModel character_for(const Clip& clip, const std::filesystem::path& input, const LoadOptions& load);

// JSON pieces of the commands' --json files: a quoted, escaped string; a number, null when not
// finite (JSON has no NaN); an array of such numbers.
std::string json_string(const std::string& s);
std::string json_number(double v);
std::string json_numbers(const std::vector<double>& v);

// What `motion retarget` and `imitate --map` print of a retargeting: scale, effector errors,
// contacts' sliding, frames under the floor.
std::string retarget_summary(const RetargetReport& report);
// The one built-in retarget map that fits a clip onto a target skeleton (said in the log); an
// Error naming the input says that none or several do.
RetargetMap fitting_builtin_map(const Clip& clip, const std::filesystem::path& input, const Skeleton& target, const std::filesystem::path& target_file);

// `mimic reconstruct --json` reports: whether a file is one, and their Markdown table (errors
// against the truth of the raw estimate and the reconstruction) for `mimic table`.
bool is_reconstruction_report(const std::filesystem::path& path);
std::string reconstruction_table(const std::vector<std::filesystem::path>& inputs, const std::vector<std::string>& names);

// Writes a clip to .mclip, DeepMimic .txt or a .svg picture, by the extension of `out`.
void write_motion(const Clip& clip, const std::filesystem::path& out);

}  // namespace mimic::app
