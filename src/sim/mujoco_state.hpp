#pragma once
// Resetting a MuJoCo state without clearing all of mjData.
struct mjModel_;
struct mjData_;

namespace mimic {

// What mj_resetData leaves for the next mj_forward, without its clearing of the whole buffer:
// MuJoCo 2.2 writes over every array of mjData there (2 MB for the humanoid, whose njmax is
// 1,000), on every episode start and every placement of a character in another skill's world,
// where it was most of the cost of a pending switch (docs/interactive.md, Cost). Cleared as
// mj_resetData clears them: time, the diagnostics and counts, and the arrays mj_forward reads
// without computing (velocities, activations, controls, applied forces, accelerations and their
// warm start, user data, sensor data, mocap poses); qpos is the model's qpos0. Everything else
// mj_forward (or mj_kinematics, for what it computes) writes before reading, so a following
// mj_forward gives the same numbers, to the bit, as after mj_resetData
// (SimWorld.SetStateForgetsEverythingBeforeIt).
void reset_state(const mjModel_* m, mjData_* d);

}  // namespace mimic
