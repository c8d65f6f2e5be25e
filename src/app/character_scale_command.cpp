// `mimic character scale`: another body from a DeepMimic character (motion/deepmimic_scale.hpp),
// its character file and, where the source has one beside it, its PD-controller file.
#include <spdlog/spdlog.h>

#include "app/commands.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "motion/deepmimic.hpp"
#include "motion/deepmimic_scale.hpp"

namespace mimic::app {

namespace {

struct ScaleArgs {
  std::filesystem::path input, output;
  std::vector<std::string> lengths;
  double mass = 1.0, gains = 0.0;
};

// "PART=FACTOR" -> (PART, FACTOR).
std::pair<std::string, double> length_rule(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) throw Error("--length " + text + ": expected JOINT_NAME_PART=FACTOR (e.g. knee=1.1)");
  try {
    std::size_t used = 0;
    const double f = std::stod(text.substr(eq + 1), &used);
    if (used != text.size() - eq - 1) throw std::invalid_argument("trailing text");
    return {text.substr(0, eq), f};
  } catch (const std::exception&) {
    throw Error("--length " + text + ": '" + text.substr(eq + 1) + "' is not a number");
  }
}

std::filesystem::path controller_of(const std::filesystem::path& character) {
  return character.parent_path() / (character.stem().string() + "_ctrl.txt");
}

}  // namespace

void add_character_scale_command(CLI::App& app) {
  CLI::App* character = app.get_subcommand("character");
  auto args = std::make_shared<ScaleArgs>();
  CLI::App* cmd = character->add_subcommand(
      "scale", "write another body from a DeepMimic character: segments lengthened or shortened, mass and gains changed");
  cmd->add_option("character", args->input, "DeepMimic character file (its NAME_ctrl.txt beside it is scaled too)")
      ->required()->check(CLI::ExistingFile);
  cmd->add_option("--length", args->lengths,
                  "JOINT_NAME_PART=FACTOR: the segment from every joint whose name contains the part onwards (its bodies and its "
                  "children's offsets) times the factor, e.g. knee=1.1 (the shin); '*' is every joint; a later one over an earlier");
  cmd->add_option("--mass", args->mass, "every body's mass times this")->capture_default_str();
  cmd->add_option("--gains", args->gains, "Kp, Kd and torque limits times this (default: the mass factor times the mean length factor)");
  cmd->add_option("-o,--output", args->output, "the new character file (.txt); its controller goes beside it as NAME_ctrl.txt")->required();
  cmd->callback([args] {
    CharacterScaling scaling;
    for (const std::string& rule : args->lengths) scaling.lengths.push_back(length_rule(rule));
    scaling.mass = args->mass;
    scaling.gains = args->gains;
    if (args->output.extension() != ".txt") throw Error(args->output.string() + ": a DeepMimic character file is a .txt");
    const ScaledCharacter scaled = scale_deepmimic_character(read_text_file(args->input), args->input.string(), scaling);
    const std::filesystem::path ctrl_in = controller_of(args->input), ctrl_out = controller_of(args->output);
    // The new character read back, and the source's controller checked against it (names, counts),
    // before either file is written.
    const DeepMimicCharacter parsed = parse_deepmimic_character(scaled.character, args->output.string());
    std::string ctrl;
    if (std::filesystem::exists(ctrl_in)) {
      const std::string text = read_text_file(ctrl_in);
      (void)parse_deepmimic_pd_gains(text, ctrl_in.string(), parsed.skeleton);
      ctrl = scale_deepmimic_controller(text, ctrl_in.string(), scaled.gains);
    }
    write_file_atomic(args->output, scaled.character);
    if (!ctrl.empty()) write_file_atomic(ctrl_out, ctrl);
    const CharacterModel ch = CharacterModel::from_deepmimic(args->output), source = CharacterModel::from_deepmimic(args->input);
    spdlog::info("wrote {}{}: {:.1f} kg (was {:.1f}), {:.3f} m tall at rest (was {:.3f}), gains and torque limits x{:.3g}",
                 args->output.string(), ctrl.empty() ? "" : " and " + ctrl_out.string(), ch.total_mass(), source.total_mass(),
                 ch.rest_height(), source.rest_height(), scaled.gains);
  });
}

}  // namespace mimic::app
