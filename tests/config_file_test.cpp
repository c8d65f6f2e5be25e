// Configs that extend a base: merging, list elements by index, and the errors.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/config_file.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/yaml_reader.hpp"
#include "error_message.hpp"

using namespace mimic;

namespace {

std::filesystem::path scratch() {
  const auto dir = std::filesystem::temp_directory_path() / "mimic_config_file_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "recipes");
  return dir;
}

YAML::Node resolved(const std::filesystem::path& path) { return YamlReader(path.string()).parse(read_config_file(path), "resolved"); }

}  // namespace

TEST(ConfigFile, WithoutExtendsTheTextIsAsWritten) {
  const auto dir = scratch();
  write_file_atomic(dir / "plain.yaml", "# a comment\nseed: 3\n");
  EXPECT_EQ(read_config_file(dir / "plain.yaml"), "# a comment\nseed: 3\n");
}

TEST(ConfigFile, TheConfigsKeysMergeOverItsBase) {
  const auto dir = scratch();
  write_file_atomic(dir / "recipes/base.yaml",
                    "seed: 1\nenv: {name: imitation, init: mocap, fall_links: [root, chest]}\n"
                    "collect: {envs: 16, threads: 2}\nrewards:\n  - {source: iccgan, expert: demos.csv, heads: 32}\n  - {source: env}\n");
  write_file_atomic(dir / "skill.yaml",
                    "extends: recipes/base.yaml\nenv: {clip: walk.txt, fall_links: [root]}\ncollect: {threads: 1}\n"
                    "rewards: {0: {expert: runs/walk.csv}}\n");
  const YAML::Node c = resolved(dir / "skill.yaml");
  EXPECT_FALSE(c["extends"].IsDefined());
  EXPECT_EQ(c["seed"].as<int>(), 1);                                   // the base's
  EXPECT_EQ(c["env"]["name"].as<std::string>(), "imitation");   // a mapping merges key by key
  EXPECT_EQ(c["env"]["clip"].as<std::string>(), "walk.txt");           // added
  ASSERT_EQ(c["env"]["fall_links"].size(), 1u);                        // a list is replaced whole
  EXPECT_EQ(c["collect"]["envs"].as<int>(), 16);
  EXPECT_EQ(c["collect"]["threads"].as<int>(), 1);                     // replaced
  ASSERT_EQ(c["rewards"].size(), 2u);                                  // index 0 merged, 1 kept
  EXPECT_EQ(c["rewards"][0]["expert"].as<std::string>(), "runs/walk.csv");
  EXPECT_EQ(c["rewards"][0]["heads"].as<int>(), 32);
  EXPECT_EQ(c["rewards"][1]["source"].as<std::string>(), "env");
  // The text says what it was resolved from.
  EXPECT_NE(read_config_file(dir / "skill.yaml").find("skill.yaml extending "), std::string::npos);
}

TEST(ConfigFile, BasesChainAndTheNearestWins) {
  const auto dir = scratch();
  write_file_atomic(dir / "recipes/a.yaml", "seed: 1\niterations: 10\ncheckpoint_every: 5\n");
  write_file_atomic(dir / "recipes/b.yaml", "extends: a.yaml\niterations: 20\n");
  write_file_atomic(dir / "c.yaml", "extends: recipes/b.yaml\nseed: 3\n");
  const YAML::Node c = resolved(dir / "c.yaml");
  EXPECT_EQ(c["seed"].as<int>(), 3);
  EXPECT_EQ(c["iterations"].as<int>(), 20);
  EXPECT_EQ(c["checkpoint_every"].as<int>(), 5);
}

TEST(ConfigFile, ABadBaseIsAnErrorNamingTheFileAndLine) {
  const auto dir = scratch();
  write_file_atomic(dir / "missing.yaml", "seed: 2\nextends: recipes/none.yaml\n");
  EXPECT_EQ(test::error_of([&] { read_config_file(dir / "missing.yaml"); }).rfind((dir / "missing.yaml").string() + ":2: 'extends': ", 0), 0u);
  write_file_atomic(dir / "recipes/x.yaml", "extends: y.yaml\n");
  write_file_atomic(dir / "recipes/y.yaml", "extends: x.yaml\n");
  EXPECT_NE(test::error_of([&] { read_config_file(dir / "recipes/x.yaml"); }).find("comes back to a config already in the chain"),
            std::string::npos);
  write_file_atomic(dir / "list.yaml", "extends: [a.yaml, b.yaml]\n");
  EXPECT_NE(test::error_of([&] { read_config_file(dir / "list.yaml"); }).find("'extends' names one base config file"), std::string::npos);
  write_file_atomic(dir / "recipes/scalar.yaml", "just a string\n");
  write_file_atomic(dir / "on_scalar.yaml", "extends: recipes/scalar.yaml\n");
  EXPECT_NE(test::error_of([&] { read_config_file(dir / "on_scalar.yaml"); }).find("is not a mapping of sections"), std::string::npos);
}

// The committed Table 2 configs hold only their clip, demonstrations, iteration count and threads:
// everything else is the ICCGAN recipe's (the one `mimic imitate` trains with).
TEST(ConfigFile, TheTable2ConfigsAreTheRecipeWithTheirClip) {
  const std::filesystem::path configs = std::filesystem::path(MIMIC_SOURCE_DIR) / "configs";
  YAML::Node recipe = YamlReader("iccgan.yaml").parse(read_text_file(configs / "recipes/iccgan.yaml"), "recipe");
  for (const char* skill : {"walk", "run", "kick", "punch"}) {
    SCOPED_TRACE(skill);
    YAML::Node c = resolved(configs / (std::string("humanoid_") + skill + "_iccgan_cpu.yaml"));
    EXPECT_EQ(c["env"]["clip"].as<std::string>(), std::string("deepmimic/motions/humanoid3d_") + skill + ".txt");
    EXPECT_EQ(c["rewards"][0]["expert"].as<std::string>(), std::string("runs/humanoid_") + skill + "_links_demos.csv");
    for (YAML::Node n : {c, recipe}) {
      n["env"].remove("clip");
      n["rewards"][0].remove("expert");
      n.remove("iterations");
      n["collect"].remove("threads");
    }
    YAML::Emitter a, b;
    a << c;
    b << recipe;
    EXPECT_EQ(std::string(a.c_str()), std::string(b.c_str()));
  }
}
