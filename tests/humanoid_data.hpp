#pragma once
// DeepMimic's humanoid and its clips from the shared data, for tests that skip without it.
#include <memory>

#include "motion/deepmimic.hpp"
#include "sim/character_model.hpp"
#include "test_data.hpp"

namespace mimic::test {

inline CharacterModel humanoid3d() {
  const auto dir = shared_data() / "deepmimic/characters";
  return CharacterModel::from_deepmimic(dir / "humanoid3d.txt", dir / "humanoid3d_ctrl.txt");
}

inline std::shared_ptr<const Clip> humanoid3d_motion(const CharacterModel& ch, const char* name) {
  return std::make_shared<const Clip>(load_deepmimic_motion(shared_data() / "deepmimic/motions" / name, ch.skeleton));
}

}  // namespace mimic::test

// Skips the calling test unless the humanoid's character file is there.
#define MIMIC_NEED_HUMANOID()                \
  std::filesystem::path mimic_humanoid_path_; \
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", mimic_humanoid_path_)
