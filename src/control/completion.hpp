#pragma once
// Motion completion (seed 003 §8): a pose seen in a still, continued by a library of skills. The
// pose is compared with every frame of each skill's clips (each joint's position in the pose's own
// heading frame relative to its root, control/pose_matching.hpp); the skill whose clips hold the
// nearest frame starts from that frame (or from the pose itself, with the frame's velocities, as
// seed 003 does: a still shows none) and drives on.
#include <memory>
#include <string>
#include <vector>

#include "control/pose_matching.hpp"
#include "mimic/runtime.hpp"
#include "motion/clip.hpp"

namespace mimic {

struct CompletionMatch {
  std::size_t skill = 0;  // index into the skills given
  std::string clip;       // the clip's name
  int frame = 0;
  double time = 0.0;      // seconds on the clip
  double distance = 0.0;  // mean joint distance (m) of the frame from the pose
};

class MotionCompletion {
 public:
  // Skills of one character whose episodes start from clips. Throws Error naming a skill whose
  // starts come from no clip, or whose character's skeleton is not the first skill's.
  explicit MotionCompletion(std::vector<std::shared_ptr<const Skill>> skills);

  // Each skill's nearest frame to `pose` (a pose of skeleton()), nearest first.
  std::vector<CompletionMatch> match(const Pose& pose) const;
  // Where the character starts: at the matched frame of the clip (its pose, velocities and past),
  // or at the still's pose (seed 003 §8) with the frame's velocities and, as its observed past,
  // the clip's poses before the frame moved by the difference between the frame and the pose (per
  // joint), so that the past ends at the pose. The clip's time goes along (a tracking skill's
  // phase). Either is turned and moved to the origin facing +X and raised out of the floor where
  // its bodies reach into it.
  enum class StartAt { Frame, Pose };
  // Starts `controller` (holding the skills by the same names) on the match's skill.
  void start(Controller& controller, const Pose& pose, const CompletionMatch& match, StartAt at = StartAt::Frame) const;

  const Skeleton& skeleton() const { return skeleton_; }

 private:
  std::vector<std::shared_ptr<const Skill>> skills_;
  std::vector<std::vector<std::shared_ptr<const Clip>>> clips_;  // per skill
  std::vector<PoseMatcher> matchers_;
  Skeleton skeleton_;
};

}  // namespace mimic
