#include "learn/trainer/train_bench.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"

namespace mimic {
namespace {

TrainBenchResult round_of(double sim_only, double train, double share_learning) {
  TrainBenchResult r;
  r.threads = 2;
  r.overlap = true;
  r.sim_only_steps_per_s = sim_only;
  r.train_samples_per_s = train;
  r.of_sim_only = r.ratio_min = r.ratio_max = train / sim_only;
  r.train_min = r.train_max = train;
  r.share_learning = share_learning;
  return r;
}

TEST(TrainBench, RoundsGiveTheirMediansAndSpread) {
  // Three rounds: the middle values are 2000 (sim only), 1500 (end to end) and 0.5 (learning); the
  // rounds' ratios are 0.75, 0.8 and 0.5.
  const TrainBenchResult m = median_of_rounds({round_of(2000, 1500, 0.5), round_of(1000, 800, 0.9), round_of(3000, 1500, 0.2)});
  EXPECT_EQ(m.threads, 2);
  EXPECT_TRUE(m.overlap);
  EXPECT_DOUBLE_EQ(m.sim_only_steps_per_s, 2000);
  EXPECT_DOUBLE_EQ(m.train_samples_per_s, 1500);
  EXPECT_DOUBLE_EQ(m.share_learning, 0.5);
  EXPECT_DOUBLE_EQ(m.of_sim_only, 0.75);
  EXPECT_DOUBLE_EQ(m.ratio_min, 0.5);
  EXPECT_DOUBLE_EQ(m.ratio_max, 0.8);
  EXPECT_DOUBLE_EQ(m.train_min, 800);
  EXPECT_DOUBLE_EQ(m.train_max, 1500);

  // Two rounds: means of the two middles. Ratios 0.4 and 0.9: median 0.65, where the medians'
  // ratio would be 1250 / 2000 = 0.625.
  const TrainBenchResult two = median_of_rounds({round_of(1000, 400, 0.1), round_of(3000, 2700, 0.3)});
  EXPECT_DOUBLE_EQ(two.sim_only_steps_per_s, 2000);
  EXPECT_DOUBLE_EQ(two.train_samples_per_s, 1550);
  EXPECT_DOUBLE_EQ(two.share_learning, 0.2);
  EXPECT_DOUBLE_EQ(two.of_sim_only, 0.65);

  // One round is itself.
  const TrainBenchResult one = median_of_rounds({round_of(2500, 2000, 0.4)});
  EXPECT_DOUBLE_EQ(one.of_sim_only, 0.8);
  EXPECT_DOUBLE_EQ(one.train_min, 2000);
  EXPECT_THROW(median_of_rounds({}), Error);
}

TEST(TrainBench, TheTableSaysHowManyRoundsAndTheirSpread) {
  TrainBenchOptions opts;
  opts.rounds = 3;
  TrainBenchResult r = round_of(2000, 1600, 0.5);
  r.threads = 1;
  r.train_min = 1500;
  r.train_max = 1700;
  r.ratio_min = 0.74;
  r.ratio_max = 0.83;
  const std::string table = format_train_benchmark(opts, {r});
  EXPECT_NE(table.find("each setting measured in 3 rounds:"), std::string::npos) << table;
  EXPECT_NE(table.find("| 1 | 1 | yes | 2000 | 1600 | 0.80 |"), std::string::npos) << table;
  EXPECT_NE(table.find("1 rank(s), 1 thread(s), overlapped: end to end 1500-1700 samples/s, of sim only 0.74-0.83"), std::string::npos) << table;
  opts.rounds = 1;
  EXPECT_EQ(format_train_benchmark(opts, {r}).find("rounds"), std::string::npos);
}

}  // namespace
}  // namespace mimic
