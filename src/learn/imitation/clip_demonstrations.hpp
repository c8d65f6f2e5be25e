#pragma once
// Expert demonstrations from motion capture (seeds 000 and 004 imitate clips, not policies): the
// environment's own observation of the clip's state (pose and velocities set kinematically) at
// every control step, paired with the next step's. Mocap has no actions: they are left out (0
// columns), so only `transition: s` or `ss` can use these files. A "links" history holds the clip's
// previous poses, as a policy's does in mid-episode (seed 004's o_{t-3:t+1}). Torch-free.
#include "env/character_env.hpp"
#include "learn/imitation/demonstrations.hpp"

namespace mimic {

// One episode per pass over the clip (`passes` >= 1; passes start a fraction of a control step
// apart, so they sample different instants). Error when the clip does not fit the character or is
// shorter than two control steps.
Demonstrations clip_demonstrations(CharacterEnv& env, const Clip& clip, int passes = 1);
// Several clips in one set (seed 004's integrated learning): each clip's passes, one after another.
Demonstrations clip_demonstrations(CharacterEnv& env, const std::vector<Clip>& clips, int passes = 1);

}  // namespace mimic
