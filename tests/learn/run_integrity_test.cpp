// A run's files stay trustworthy: a damaged checkpoint or model is refused before anything of it
// is used or rewritten (the previous checkpoint offered instead), a metrics.csv that does not read
// back whole stops a resume without losing a row, a resumed run's TensorBoard steps appear once,
// and configs that cannot be meant (a key given twice, networks larger than the machine) are
// named errors.
#include <gtest/gtest.h>

#include <fstream>
#include <map>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/tensorboard.hpp"
#include "learn/trainer/run_log.hpp"
#include "learn/trainer/trainer.hpp"
#include "../error_message.hpp"
#include "../test_data.hpp"
#include "trainer_access.hpp"

using namespace mimic;
using mimic::test::error_of;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

std::string walker(int iterations, int checkpoint_every) {
  return "seed: 5\niterations: " + std::to_string(iterations) + "\ncheckpoint_every: " + std::to_string(checkpoint_every) +
         "\nenv: {name: planar_walker}\ncollect: {envs: 4, threads: 1, samples: 256}\npolicy: {hidden: [16]}\nvalue: {hidden: [16]}\n"
         "ppo: {epochs: 2, value_epochs: 2, minibatch: 64}\n";
}

TrainConfig integrity_config(const std::string& text) { return parse_train_config(text, "walker.yaml"); }

// A byte of the file flipped at `at` (a fraction of its size).
void flip_byte(const std::filesystem::path& p, double at) {
  std::string bytes = read_text_file(p);
  bytes[static_cast<std::size_t>(at * static_cast<double>(bytes.size()))] ^= 0x20;
  std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
}

}  // namespace

// Bytes flipped inside a checkpoint's weights: eval measured a return of 2,065 +- 1,760 on it
// instead of 4,717, and a resume rewrote it with fresh CRCs. Now every reader refuses it.
TEST(RunIntegrity, AFlippedByteInACheckpointIsRefusedAndTheResumeOffersThePreviousOne) {
  const auto dir = test::temp_dir("integrity_flip");
  TrainOptions o;
  o.run_dir = dir;
  Trainer(integrity_config(walker(4, 2)), o).run();
  ASSERT_TRUE(std::filesystem::exists(dir / "checkpoint.prev.pt"));  // iteration 2's, beside iteration 4's
  const std::string before = read_text_file(dir / "checkpoint.pt");
  flip_byte(dir / "checkpoint.pt", 0.5);
  const std::string damaged = read_text_file(dir / "checkpoint.pt");
  o.resume = true;
  const std::string what = error_of([&] { Trainer t(integrity_config(walker(4, 2)), o); });
  EXPECT_TRUE(contains(what, (dir / "checkpoint.pt").string() + ": checkpoint is damaged, nothing of it was used")) << what;
  EXPECT_TRUE(contains(what, "fails the CRC-32 recorded when it was written")) << what;
  EXPECT_TRUE(contains(what, "the previous checkpoint " + (dir / "checkpoint.prev.pt").string() + " is intact (iteration 2)")) << what;
  EXPECT_EQ(read_text_file(dir / "checkpoint.pt"), damaged);  // not rewritten
  EXPECT_TRUE(contains(error_of([&] { Trainer::from_run(dir); }), "checkpoint is damaged")) << "eval, render, record, score";
  // As offered: the previous checkpoint resumes, and the metrics go back to its iteration.
  std::filesystem::rename(dir / "checkpoint.prev.pt", dir / "checkpoint.pt");
  Trainer resumed(integrity_config(walker(4, 2)), o);
  EXPECT_EQ(resumed.iteration(), 2);
  EXPECT_EQ(read_metrics_csv(dir / "metrics.csv").rows.size(), 2u);
  // An exported model is checked the same way.
  resumed.run();
  resumed.export_model(dir / "model.pt");
  flip_byte(dir / "model.pt", 0.6);
  Trainer other(integrity_config(walker(4, 2)));
  EXPECT_TRUE(contains(error_of([&] { other.load_checkpoint(dir / "model.pt"); }), "model.pt: checkpoint is damaged")) << before.size();
}

// A corrupted metrics.csv header on resume dropped every earlier row and exited 0.
TEST(RunIntegrity, AResumeRefusesAMetricsFileThatDoesNotReadBackWhole) {
  const auto dir = test::temp_dir("integrity_metrics");
  TrainOptions o;
  o.run_dir = dir;
  Trainer(integrity_config(walker(3, 1)), o).run();
  const std::string good = read_text_file(dir / "metrics.csv");
  o.resume = true;
  auto resume_with = [&](const std::string& csv) {
    std::ofstream(dir / "metrics.csv", std::ios::trunc) << csv;
    const std::string what = error_of([&] { Trainer t(integrity_config(walker(5, 1)), o); });
    EXPECT_EQ(read_text_file(dir / "metrics.csv"), csv) << "the file was changed";
    return what;
  };
  std::string header = good;
  header.replace(0, 9, "it\x01ration");
  EXPECT_TRUE(contains(resume_with(header), "metrics.csv:1: not a metrics header")) << resume_with(header);
  std::string row = good;
  row.replace(row.find("\n2,") + 1, 1, "x");
  const std::string bad_row = resume_with(row);
  EXPECT_TRUE(contains(bad_row, "metrics.csv:3: 'x")) << bad_row;
  EXPECT_TRUE(contains(bad_row, "the run was not resumed, so that no row of it is lost")) << bad_row;
  // A last row cut by a kill (no newline) is the one thing dropped unread.
  std::ofstream(dir / "metrics.csv", std::ios::trunc) << good << "4,12,0.";
  Trainer t(integrity_config(walker(5, 1)), o);
  EXPECT_EQ(read_text_file(dir / "metrics.csv"), good);
}

// TensorBoard got the resumed iterations twice: the old event file kept the steps after the
// checkpoint, and the resumed run wrote them again.
TEST(RunIntegrity, AResumedRunWritesEveryTensorBoardStepOnce) {
  const auto dir = test::temp_dir("integrity_tensorboard");
  TrainOptions o;
  o.run_dir = dir;
  {
    Trainer t(integrity_config(walker(5, 2)), o);
    for (int i = 0; i < 3; ++i) t.iterate();  // checkpoint at 2, steps 1-3 logged: as a kill after iteration 3
  }
  o.resume = true;
  Trainer resumed(integrity_config(walker(5, 2)), o);
  ASSERT_EQ(resumed.iteration(), 2);
  resumed.run();
  std::map<std::pair<std::string, std::int64_t>, int> seen;
  for (const auto& f : std::filesystem::directory_iterator(dir / "tensorboard"))
    for (const TensorBoardScalar& s : read_tensorboard_scalars(f.path())) ++seen[{s.tag, s.step}];
  for (std::int64_t step = 1; step <= 5; ++step) EXPECT_EQ((seen[{"return", step}]), 1) << "step " << step;
  for (const auto& [key, count] : seen) EXPECT_EQ(count, 1) << key.first << " at step " << key.second;
}

TEST(RunIntegrity, ConfigsThatCannotBeMeantAreNamedErrors) {
  // `seed: 2` then `seed: 3` was accepted (seed 2 trained).
  EXPECT_TRUE(contains(error_of([] { integrity_config("seed: 2\nseed: 3\n"); }), "walker.yaml:2: key 'seed' is given twice (first on line 1)"));
  EXPECT_TRUE(contains(error_of([] { override_config("seed: 2\n", "c.yaml", {"ppo={clip: 0.1, clip: 0.2}"}); }), "key 'clip' is given twice"));
  // `hidden: [65536, 65536]` passed validation and died in the allocator.
  const std::string huge = walker(1, 1) + "policy: {hidden: [65536, 65536, 65536]}\n";
  const std::string text = huge.substr(0, huge.find("policy: {hidden: [16]}\n")) + huge.substr(huge.find("value:"));
  const std::string what = error_of([&] { Trainer t(integrity_config(text)); });
  EXPECT_TRUE(contains(what, "walker.yaml: the policy (17 -> 65536 -> 65536 -> 65536 -> 6)")) << what;
  EXPECT_TRUE(contains(what, "GiB of memory")) << what;
}
