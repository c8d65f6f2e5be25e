#include "learn/trainer/ranks.hpp"

#include <atomic>
#include <cstdlib>

#include "core/error.hpp"

#ifdef MIMIC_WITH_MPI
#include <mpi.h>
#endif

namespace mimic::ranks {

namespace {

int g_rank = 0, g_size = 1;
std::atomic<long long> g_sums{0}, g_bytes{0};  // the policy's and the value's threads both count

void count(std::size_t bytes) {
  ++g_sums;
  g_bytes += static_cast<long long>(bytes);
}

// Set by mpirun (Open MPI, and the PMI/PMIx launchers of MPICH and Slurm).
bool started_by_mpirun() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

#ifdef MIMIC_WITH_MPI
bool g_started = false;
MPI_Comm g_comms[4];

MPI_Comm communicator(Channel c) { return g_comms[static_cast<int>(c)]; }

void check_mpi(int rc, const char* what) {
  if (rc == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(rc, text, &length);
  throw Error(std::string("MPI: ") + what + " failed: " + std::string(text, static_cast<std::size_t>(length)));
}
#endif

}  // namespace

bool available() {
#ifdef MIMIC_WITH_MPI
  return true;
#else
  return false;
#endif
}

void init(int& argc, char**& argv) {
  if (!started_by_mpirun()) return;
#ifdef MIMIC_WITH_MPI
  int provided = 0;
  check_mpi(MPI_Init_thread(&argc, &argv, MPI_THREAD_MULTIPLE, &provided), "MPI_Init_thread");
  g_started = true;
  if (provided < MPI_THREAD_MULTIPLE)
    throw Error("MPI: this MPI library does not support calls from several threads (MPI_THREAD_MULTIPLE), which the concurrent policy and "
                "value updates need");
  MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_size);
  for (MPI_Comm& c : g_comms) check_mpi(MPI_Comm_dup(MPI_COMM_WORLD, &c), "MPI_Comm_dup");
#else
  (void)argc, (void)argv;
  throw Error("started by mpirun, but this mimic was built without MPI (install libopenmpi-dev: scripts/setup.sh, then rebuild)");
#endif
}

void finalize() {
#ifdef MIMIC_WITH_MPI
  if (!g_started) return;
  for (MPI_Comm& c : g_comms) MPI_Comm_free(&c);
  MPI_Finalize();
  g_started = false;
#endif
}

void abort_all(int code) {
#ifdef MIMIC_WITH_MPI
  if (g_started && g_size > 1) MPI_Abort(MPI_COMM_WORLD, code);
#else
  (void)code;
#endif
}

int rank() { return g_rank; }
int size() { return g_size; }

Traffic traffic() { return {g_sums.load(), g_bytes.load()}; }

void sum(std::span<double> values, Channel channel) {
  if (g_size == 1 || values.empty()) return;
  count(values.size_bytes());
#ifdef MIMIC_WITH_MPI
  check_mpi(MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_SUM, communicator(channel)), "a sum of doubles");
#else
  (void)channel;
#endif
}

void sum(std::span<float> values, Channel channel) {
  if (g_size == 1 || values.empty()) return;
  count(values.size_bytes());
#ifdef MIMIC_WITH_MPI
  check_mpi(MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_FLOAT, MPI_SUM, communicator(channel)), "a sum of floats");
#else
  (void)channel;
#endif
}

double sum(double value, Channel channel) {
  sum(std::span<double>(&value, 1), channel);
  return value;
}

void continue_alone() { g_size = 1; }

void barrier() {
  if (g_size == 1) return;
#ifdef MIMIC_WITH_MPI
  check_mpi(MPI_Barrier(communicator(Channel::statistics)), "a barrier");
#endif
}

double minimum(double value) {
  if (g_size == 1) return value;
  count(sizeof value);
#ifdef MIMIC_WITH_MPI
  check_mpi(MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_MIN, communicator(Channel::statistics)), "a minimum");
#endif
  return value;
}

bool any(bool value) { return sum(value ? 1.0 : 0.0) > 0.0; }

std::vector<std::string> gather(const std::string& mine) {
  if (g_size == 1) return {mine};
#ifdef MIMIC_WITH_MPI
  const MPI_Comm c = communicator(Channel::statistics);
  int length = static_cast<int>(mine.size());
  std::vector<int> lengths(static_cast<std::size_t>(g_size)), offsets(static_cast<std::size_t>(g_size));
  check_mpi(MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, c), "gathering lengths");
  std::string all;
  if (g_rank == 0) {
    int at = 0;
    for (int k = 0; k < g_size; ++k) offsets[static_cast<std::size_t>(k)] = at, at += lengths[static_cast<std::size_t>(k)];
    all.resize(static_cast<std::size_t>(at));
  }
  check_mpi(MPI_Gatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0, c), "gathering states");
  if (g_rank != 0) return {};
  std::vector<std::string> out;
  for (int k = 0; k < g_size; ++k)
    out.push_back(all.substr(static_cast<std::size_t>(offsets[static_cast<std::size_t>(k)]), static_cast<std::size_t>(lengths[static_cast<std::size_t>(k)])));
  return out;
#else
  return {mine};
#endif
}

}  // namespace mimic::ranks
