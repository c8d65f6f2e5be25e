#pragma once
// Policy distillation by DAgger (Ross et al. 2011; Rusu et al. 2016): one student policy learns
// to act as several single-skill teachers, teacher k under behaviour context k, so that skills
// trained apart (a walk, a run) become one policy that switches on command. Each round the
// student acts (sampled actions) in its own environment, whose context env re-draws the context
// during episodes; every state it visits is labelled with its context's teacher's mean action, on
// the student's frame without the one-hot; the student's mean regresses the labelled states kept
// so far (behavioural cloning on the aggregate). Because the states are the student's own, it
// also learns what each teacher does from the other skill's states: the switches.
// A student without contexts takes one teacher (plain distillation, e.g. into another network).
// Torch-free: teachers are functions from an input to an action.
#include <functional>
#include <vector>

#include "learn/imitation/demonstrations.hpp"
#include "learn/imitation/imitation_eval.hpp"
#include "learn/trainer/trainer.hpp"

namespace mimic {

// `states` with each row's action replaced by its teacher's: teacher k for the rows whose context
// slice (`layout`'s part "context") is the one-hot of k, given the row without that slice; with no
// context slice, the single teacher on the whole row. Errors: a teacher count that is not the
// context's width (or 1), a row whose context is not a one-hot, a teacher whose action has
// another size.
Demonstrations label_by_teachers(const Demonstrations& states, const std::vector<ObservationSlice>& layout,
                                 const std::vector<PolicyFunction>& teachers);

struct DistillOptions {
  int rounds = 100;
  int episodes = 16;    // student episodes per round
  int keep = 40'000;    // labelled states kept, the newest (DAgger's aggregate, bounded)
  int epochs = 2;       // passes over the kept states per round
  double lr = 1e-4;     // Adam
  int batch = 256;
  std::uint64_t seed = 1;
  int first_round = 1;           // a resumed distillation goes on from its next round
  long long samples_before = 0;  // and its step count
};

struct DistillRound {
  int round = 0;                      // 1-based
  long long samples = 0;              // student steps so far
  int kept = 0;                       // labelled states regressed this round
  double episode_length = 0, episode_return = 0;  // the round's student episodes (sampled actions)
  int falls = 0;                      // of them, episodes that ended in a fall
  double loss = 0;                    // mean squared action error, last epoch
};

// Runs rounds `o.first_round` to `o.rounds` on `student` (a policy of one frame); `after_round` gets each round's
// figures and returns false to stop early. Errors as label_by_teachers, and for bad options.
void distill(Trainer& student, const std::vector<PolicyFunction>& teachers, const DistillOptions& o,
             const std::function<bool(const DistillRound&)>& after_round);

}  // namespace mimic
