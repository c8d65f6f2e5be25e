// The generators of ranks other than 0 (ranks.hpp), which a checkpoint keeps beside rank 0's, so
// that a run resumed over as many ranks goes on as it would have.
#include <array>
#include <sstream>

#include "core/error.hpp"
#include "learn/networks/archive_util.hpp"
#include "learn/trainer/ranks.hpp"
#include "learn/trainer/trainer_impl.hpp"

namespace mimic {

std::uint64_t rank_seed(std::uint64_t seed) {
  return ranks::rank() == 0 ? seed : seed ^ (std::uint64_t{0x9e3779b97f4a7c15} * static_cast<std::uint64_t>(ranks::rank()));
}

// One generator's state per line: action noise, minibatches, then each environment's.
std::string generator_state(const Trainer::Impl& t) {
  std::string out = archive::rng_text(t.noise_rng) + "\n" + archive::rng_text(t.shuffle_rng) + "\n";
  for (const std::string& s : t.collector->rng_states()) out += s + "\n";
  return out;
}

void set_generator_state(Trainer::Impl& t, const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  if (lines.size() != static_cast<std::size_t>(t.collector->envs()) + 2)
    throw Error("rank " + std::to_string(ranks::rank()) + "'s saved generators are for " + std::to_string(lines.size() < 2 ? 0 : lines.size() - 2) +
                " environments, not " + std::to_string(t.collector->envs()));
  archive::set_rng(t.noise_rng, lines[0], "rank noise");
  archive::set_rng(t.shuffle_rng, lines[1], "rank minibatches");
  t.collector->set_rng_states(std::vector<std::string>(lines.begin() + 2, lines.end()));
}

void reseed_generators(Trainer::Impl& t) {
  std::seed_seq seq{rank_seed(t.cfg.seed), static_cast<std::uint64_t>(t.iteration), std::uint64_t{0x726573756d65}};  // "resume"
  std::array<std::uint64_t, 2> own{};
  seq.generate(own.begin(), own.end());
  t.noise_rng.seed(own[0]);
  t.shuffle_rng.seed(own[1]);
  std::seed_seq env_seq{own[0], own[1], std::uint64_t{0x656e76}};  // "env"
  std::vector<std::uint64_t> seeds(static_cast<std::size_t>(t.collector->envs()));
  env_seq.generate(seeds.begin(), seeds.end());
  std::vector<std::string> states;
  for (std::uint64_t s : seeds) states.push_back(archive::rng_text(std::mt19937_64(s)));
  t.collector->set_rng_states(states);
}

}  // namespace mimic
