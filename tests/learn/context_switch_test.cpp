// Behaviour switches measured (mimic eval --switch): a puck whose "policy" moves it at 1 m/s along
// x in context 0 and at 3 m/s along y in context 1, so every figure is known by hand.
#include "learn/imitation/context_switch.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "env/mjcf_env.hpp"

using namespace mimic;

namespace {

// A puck on two slide joints, no gravity, no friction: the action is its velocity, held for a
// control step of 5 x 0.01 s. It "falls" past y = fall_y; episodes last `limit` steps.
class PuckEnv : public MjcfEnv {
 public:
  PuckEnv(double fall_y, int limit)
      : MjcfEnv("puck",
                R"(<mujoco><option gravity="0 0 0" timestep="0.01"/><worldbody><body name="puck">
                   <joint name="x" type="slide" axis="1 0 0"/><joint name="y" type="slide" axis="0 1 0"/>
                   <geom type="sphere" size="0.1" mass="1" contype="0" conaffinity="0"/></body></worldbody></mujoco>)",
                5),
        fall_y_(fall_y), limit_(limit) {}
  int observation_size() const override { return 2; }
  int action_size() const override { return 2; }
  std::vector<ObservationSlice> observation_layout() const override { return {{"position", 0, 2}}; }
  Eigen::VectorXd reset(std::mt19937_64&) override {
    reset_data();
    steps_ = 0;
    return qpos();
  }
  StepResult step(const Eigen::VectorXd& velocity) override {
    set_state(qpos(), velocity);
    simulate(Eigen::VectorXd(0));
    StepResult r;
    r.observation = qpos();
    r.reward_terms = {{"none", 0.0}};
    if (qpos()[1] > fall_y_) r.termination = Termination::Fall;
    else if (++steps_ >= limit_) r.termination = Termination::TimeLimit;
    return r;
  }

 private:
  double fall_y_;
  int limit_, steps_ = 0;
};

// The context the newest frame of a stacked input shows (two contexts, after a 2-value frame).
StackedPolicy by_context(std::vector<int>* seen) {
  return [seen](const Eigen::VectorXd& input) {
    const int c = input[input.size() - 1] == 1.0 ? 1 : 0;
    if (seen) seen->push_back(c);
    return c == 0 ? Eigen::Vector2d(1.0, 0.0) : Eigen::Vector2d(0.0, 3.0);
  };
}

}  // namespace

TEST(ContextSwitch, HoldsEachContextAndMeasuresTheSpeedInEachHold) {
  ContextEnv env(std::make_unique<PuckEnv>(100.0, 40), 2, 3);  // draws every 3 steps, overridden by the holds
  std::vector<int> seen;
  const SwitchReport r = measure_switch(env, by_context(&seen), 2, 0, 1, 3, 20);
  EXPECT_EQ(r.trials, 3);
  EXPECT_EQ(r.hold_steps, 20);
  EXPECT_NEAR(r.hold_seconds, 1.0, 1e-12);  // 20 steps of 0.05 s
  EXPECT_EQ(r.fell_before, 0);
  EXPECT_EQ(r.fell_after, 0);
  ASSERT_EQ(r.speed_before.size(), 3u);
  ASSERT_EQ(r.speed_after.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(r.speed_before[static_cast<std::size_t>(i)], 1.0, 1e-9);
    EXPECT_NEAR(r.speed_after[static_cast<std::size_t>(i)], 3.0, 1e-9);
  }
  // The policy saw context 0 for the first hold and 1 from the step after the switch on.
  ASSERT_EQ(seen.size(), 120u);
  for (std::size_t t = 0; t < seen.size(); ++t) EXPECT_EQ(seen[t], t % 40 <= 20 ? 0 : 1) << "step " << t;
  EXPECT_FALSE(env.context_held());  // released: the env draws its own contexts again
}

TEST(ContextSwitch, CountsFallsOnEachSideOfTheSwitch) {
  // At 3 m/s along y the puck passes y = 2 on the 14th step after the switch (0.15 m a step).
  ContextEnv after(std::make_unique<PuckEnv>(2.0, 40), 2, 0);
  SwitchReport r = measure_switch(after, by_context(nullptr), 1, 0, 1, 4, 20);
  EXPECT_EQ(r.fell_before, 0);
  EXPECT_EQ(r.fell_after, 4);
  EXPECT_EQ(r.speed_before.size(), 4u);
  EXPECT_TRUE(r.speed_after.empty());
  // The other way round it falls in the first hold and never switches.
  r = measure_switch(after, by_context(nullptr), 1, 1, 0, 4, 20);
  EXPECT_EQ(r.fell_before, 4);
  EXPECT_EQ(r.fell_after, 0);
  EXPECT_TRUE(r.speed_before.empty());
}

TEST(ContextSwitch, RejectsWhatItCannotMeasure) {
  ContextEnv env(std::make_unique<PuckEnv>(100.0, 30), 2, 0);
  const StackedPolicy act = by_context(nullptr);
  EXPECT_THROW(measure_switch(env, act, 1, 0, 0, 1, 10), Error);  // no switch
  EXPECT_THROW(measure_switch(env, act, 1, 0, 2, 1, 10), Error);  // no context 2
  EXPECT_THROW(measure_switch(env, act, 1, 0, 1, 0, 10), Error);  // no trials
  EXPECT_THROW(measure_switch(env, act, 1, 0, 1, 1, 1), Error);   // a hold too short to measure
  try {
    (void)measure_switch(env, act, 1, 0, 1, 1, 20);  // the episode's 30 steps end before the trial's 40
    FAIL() << "a time limit inside the trial must be an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ended (time_limit) after 30 steps"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(env.context_held());
}
