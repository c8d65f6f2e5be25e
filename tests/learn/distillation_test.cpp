// Policy distillation (DAgger): each state labelled by its context's teacher, given the state
// without the one-hot; a student that learns two teachers' behaviours, one per context; errors.
#include <gtest/gtest.h>

#include <iostream>

#include "core/error.hpp"
#include "env/context_env.hpp"
#include "learn/imitation/distillation.hpp"
#include "learn/trainer/train_config.hpp"
#include "toy_env.hpp"
#include "../error_message.hpp"
#include "trainer_access.hpp"

using namespace mimic;
using mimic::test::error_of;

namespace {

// Teacher k drives the point mass onto the orbit of radius k + 1: the expert's -x, plus a push
// along v that grows the orbit inside that radius and shrinks it outside.
PolicyFunction orbit_teacher(int k) {
  return [k](const Eigen::VectorXd& s) {
    EXPECT_EQ(s.size(), 2);  // (x, v): the student's state without its one-hot
    const double radius = std::hypot(s[0], s[1]);
    return Eigen::VectorXd::Constant(1, -s[0] + 2.0 * s[1] * (k + 1 - radius));
  };
}

}  // namespace

TEST(Distillation, EachStateIsLabelledByItsContextsTeacherWithoutTheOneHot) {
  Demonstrations d;
  d.obs.resize(3, 4);
  d.obs << 0.5, 0.1, 1, 0,  //
      0.5, 0.1, 0, 1,       //
      -2.0, 0.0, 1, 0;
  d.action = Eigen::MatrixXd::Zero(3, 1);
  d.next_obs = d.obs;
  d.episode = {0, 0, 1};
  const std::vector<ObservationSlice> layout = {{"position", 0, 1}, {"velocity", 1, 1}, {"context", 2, 2}};
  const Demonstrations out = label_by_teachers(d, layout, {orbit_teacher(0), orbit_teacher(1)});
  const double r = std::hypot(0.5, 0.1);
  EXPECT_NEAR(out.action(0, 0), -0.5 + 0.2 * (1 - r), 1e-12);  // context 0: the orbit of radius 1
  EXPECT_NEAR(out.action(1, 0), -0.5 + 0.2 * (2 - r), 1e-12);  // context 1: radius 2
  EXPECT_NEAR(out.action(2, 0), 2.0, 1e-12);                   // v = 0: the expert's -x alone
  EXPECT_EQ(out.obs, d.obs);                                   // the states are kept as visited
}

TEST(Distillation, TeachersMustFitTheStudentsContextsAndActions) {
  Demonstrations d;
  d.obs.resize(1, 4);
  d.obs << 0.5, 0.1, 1, 0;
  d.action = Eigen::MatrixXd::Zero(1, 1);
  d.next_obs = d.obs;
  d.episode = {0};
  const std::vector<ObservationSlice> layout = {{"state", 0, 2}, {"context", 2, 2}};
  EXPECT_NE(error_of([&] { label_by_teachers(d, layout, {orbit_teacher(0)}); }).find("1 teachers for a student with 2 behaviour contexts"),
            std::string::npos);
  const PolicyFunction two_actions = [](const Eigen::VectorXd&) { return Eigen::VectorXd::Zero(2).eval(); };
  d.obs(0, 2) = 0;
  d.obs(0, 3) = 1;
  EXPECT_NE(error_of([&] { label_by_teachers(d, layout, {orbit_teacher(0), two_actions}); }).find("teacher 1 gives 2 action values, the student 1"),
            std::string::npos);
  d.obs(0, 2) = 0.5;  // not a one-hot
  EXPECT_NE(error_of([&] { label_by_teachers(d, layout, {orbit_teacher(0), orbit_teacher(1)}); }).find("state 0's context is not a one-hot"),
            std::string::npos);
  // Without contexts: one teacher, given the whole state.
  Demonstrations plain = d;
  plain.obs = d.obs.leftCols(2);
  plain.next_obs = plain.obs;
  EXPECT_NEAR(label_by_teachers(plain, {{"state", 0, 2}}, {orbit_teacher(0)}).action(0, 0), -0.5 + 0.2 * (1 - std::hypot(0.5, 0.1)), 1e-12);
  EXPECT_NE(error_of([&] { label_by_teachers(plain, {{"state", 0, 2}}, {orbit_teacher(0), orbit_teacher(1)}); })
                .find("2 teachers for a student without behaviour contexts (one teacher)"),
            std::string::npos);
}

// Learning, not only running: a student that starts acting the same in both contexts ends up
// holding each teacher's orbit under that teacher's context, from its own states alone.
TEST(DistillationLearning, OneStudentLearnsTwoTeachersBehavioursFromItsOwnStates) {
  TrainOptions o;
  o.env_factory = [] { return std::make_unique<ContextEnv>(std::make_unique<test::OscillatorEnv>(), 2, 10); };
  Trainer student(parse_train_config("collect: {envs: 4, samples: 64}\npolicy: {hidden: [32, 32], activation: tanh, log_std: -1.5}\n", "s.yaml"),
                  o);
  const auto radius = [&](int context) {
    return test::held_orbit_radius([&](const Eigen::VectorXd& s) { return test::act(student, s); }, context);
  };
  const double small_before = radius(0), large_before = radius(1);
  DistillOptions d;
  d.rounds = 12, d.episodes = 8, d.epochs = 30, d.lr = 3e-3, d.batch = 64;
  std::vector<DistillRound> rounds;
  distill(student, {orbit_teacher(0), orbit_teacher(1)}, d, [&](const DistillRound& r) {
    rounds.push_back(r);
    return true;
  });
  const double small_after = radius(0), large_after = radius(1);
  std::cout << "radius under context 0 (teacher: 1) " << small_before << " -> " << small_after << "; under context 1 (teacher: 2) "
            << large_before << " -> " << large_after << "; loss " << rounds.front().loss << " -> " << rounds.back().loss << "\n";
  EXPECT_LT(std::abs(large_before - small_before), 0.3);  // untrained: the context changes little
  EXPECT_NEAR(small_after, 1.0, 0.15);
  EXPECT_NEAR(large_after, 2.0, 0.2);
  ASSERT_EQ(rounds.size(), 12u);
  EXPECT_EQ(rounds.back().round, 12);
  EXPECT_EQ(rounds.back().samples, 12 * 8 * test::OscillatorEnv::kLength);  // every student step is labelled
  EXPECT_EQ(rounds.back().kept, 12 * 8 * test::OscillatorEnv::kLength);
  EXPECT_LT(rounds.back().loss, 0.1 * rounds.front().loss);
}

TEST(Distillation, StopsWhenAskedAndKeepsOnlyTheNewestStates) {
  TrainOptions o;
  o.env_factory = [] { return std::make_unique<ContextEnv>(std::make_unique<test::OscillatorEnv>(), 2, 10); };
  Trainer student(parse_train_config("collect: {envs: 2, samples: 64}\npolicy: {hidden: [8]}\n", "s.yaml"), o);
  DistillOptions d;
  d.rounds = 10, d.episodes = 2, d.keep = 100, d.epochs = 1;
  std::vector<DistillRound> rounds;
  distill(student, {orbit_teacher(0), orbit_teacher(1)}, d, [&](const DistillRound& r) {
    rounds.push_back(r);
    return rounds.size() < 3;
  });
  ASSERT_EQ(rounds.size(), 3u);
  EXPECT_EQ(rounds[0].kept, 80);   // two episodes of 40 steps
  EXPECT_EQ(rounds[1].kept, 100);  // the oldest 60 dropped
  EXPECT_EQ(rounds[2].samples, 240);
  d.keep = 0;
  EXPECT_THROW(distill(student, {orbit_teacher(0), orbit_teacher(1)}, d, [](const DistillRound&) { return true; }), Error);
}
