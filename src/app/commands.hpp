#pragma once
// Sub-commands of the `mimic` command line, one registration function per group.
#include <CLI/CLI.hpp>

#include "motion/clip_io.hpp"

namespace mimic::app {

void add_motion_commands(CLI::App& app);
void add_demo_command(CLI::App& app);

// Options every command that reads a motion file accepts.
void add_load_options(CLI::App& cmd, LoadOptions& opts);

// A human-readable summary of a clip (several lines).
std::string clip_summary(const Clip& clip);

// Writes a clip to .mclip, DeepMimic .txt or a .svg picture, by the extension of `out`.
void write_motion(const Clip& clip, const std::filesystem::path& out);

}  // namespace mimic::app
