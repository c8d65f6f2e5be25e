#pragma once
// The processes of one training run started by `mpirun -np N mimic train CONFIG` (distributed
// PPO as seed 004 trained with workers and DeepMimic with MPI). Every rank collects with its own
// environments and keeps its own copy of the networks; what the copies must agree on is summed
// over the ranks here: gradients every minibatch, normaliser moments, episode statistics, the
// decision to stop. Started without mpirun, or built without MPI, there is one rank and every
// call below returns its input.
#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace mimic::ranks {

// Independent streams of collective calls, each on its own communicator: the policy's and the
// value's updates run on two threads at once, and their sums must not meet.
enum class Channel { policy, value, discriminator, statistics };

// MPI_Init when this process was started by mpirun (its environment says so); a no-op otherwise.
// Call once, first thing in main. Error when the build has no MPI but mpirun started it.
void init(int& argc, char**& argv);
// MPI_Finalize where init started MPI.
void finalize();
// Ends every rank of the run (MPI_Abort): an error on one rank must not leave the others waiting
// in a sum. Returns only where MPI is not running.
void abort_all(int code);

int rank();
int size();
inline bool many() { return size() > 1; }
// Whether this build can run over several ranks.
bool available();

// Element-wise sums over the ranks, in place; every rank gets the result.
void sum(std::span<double> values, Channel channel = Channel::statistics);
void sum(std::span<float> values, Channel channel);
double sum(double value, Channel channel = Channel::statistics);
// Waits until every rank has come here (after rank 0 has written what the others read).
void barrier();
// From here on this process works alone, as a run of one rank (rank 0 after training: the
// export, evaluation and video of `mimic imitate`); the other ranks have finished their part.
void continue_alone();
// The smallest of the ranks' values.
double minimum(double value);
// Whether any rank says true.
bool any(bool value);
// Every rank's `mine`, in rank order, at rank 0; elsewhere empty.
std::vector<std::string> gather(const std::string& mine);

// What this rank has put into sums over several ranks so far: calls and bytes (each rank's
// share; what crosses the network depends on the MPI library's algorithm, docs/scaling.md).
struct Traffic {
  long long sums = 0, bytes = 0;
};
Traffic traffic();

}  // namespace mimic::ranks
