// `mimic train` and `mimic imitate` under SIGTERM and SIGINT, run as a scheduler or a user would:
// the first signal stops the run within a collection step (an iteration here would take many
// minutes) and saves the last completed iteration, and the command exits 128 + the signal; a
// second exits at once, leaving the checkpoint on disk intact.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fcntl.h>
#include <fstream>
#include <optional>
#include <thread>

#include "core/file_io.hpp"
#include "core/zip_integrity.hpp"
#include "motion/builtin.hpp"
#include "motion/clip_io.hpp"
#include "test_data.hpp"

namespace {

using Clock = std::chrono::steady_clock;
const std::string kMimic = std::string(MIMIC_BINARY_DIR) + "/src/mimic";

// `mimic args...` with its output in `log`.
pid_t start(const std::vector<std::string>& args, const std::filesystem::path& log) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1), ::dup2(fd, 2);
    std::vector<char*> argv{const_cast<char*>(kMimic.c_str())};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(kMimic.c_str(), argv.data());
    ::_exit(127);
  }
  return pid;
}

bool wait_for_text(const std::filesystem::path& log, const std::string& text, double seconds) {
  const auto end = Clock::now() + std::chrono::duration<double>(seconds);
  while (Clock::now() < end) {
    if (std::filesystem::exists(log) && mimic::read_text_file(log).find(text) != std::string::npos) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

// The exit status, or nothing when the process is still running after `seconds` (then killed).
std::optional<int> wait_exit(pid_t pid, double seconds) {
  const auto end = Clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  while (Clock::now() < end) {
    if (::waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, &status, 0);
  return std::nullopt;
}

std::string text_of(const std::filesystem::path& p) { return mimic::read_text_file(p); }

}  // namespace

TEST(TrainSignals, SigtermStopsWithinAStepAndASecondSignalExitsAtOnce) {
  const auto dir = mimic::test::temp_dir("train_signals");
  // Five million samples an iteration: minutes of collection before the first checkpoint.
  std::ofstream(dir / "walker.yaml") << "iterations: 3\nenv: {name: planar_walker}\ncollect: {envs: 4, threads: 1, samples: 5000000}\n"
                                        "policy: {hidden: [16]}\nvalue: {hidden: [16]}\n";
  const auto run = dir / "run";
  const pid_t pid = start({"train", (dir / "walker.yaml").string(), "-o", run.string()}, dir / "first.log");
  ASSERT_TRUE(wait_for_text(dir / "first.log", "training from iteration 0", 120)) << text_of(dir / "first.log");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const auto sent = Clock::now();
  ::kill(pid, SIGTERM);
  const std::optional<int> status = wait_exit(pid, 60);
  const double seconds = std::chrono::duration<double>(Clock::now() - sent).count();
  ASSERT_TRUE(status.has_value()) << "still running a minute after SIGTERM:\n" << text_of(dir / "first.log");
  // Saved and ended cleanly, but not finished: 128 + SIGTERM, so that a script stops there.
  EXPECT_EQ(*status, 128 + SIGTERM) << text_of(dir / "first.log");
  std::cout << "[ figures  ] exited " << seconds << " s after SIGTERM\n";
  const std::string log = text_of(dir / "first.log");
  EXPECT_NE(log.find("stop requested (stopped during collection, "), std::string::npos) << log;
  EXPECT_NE(log.find("saved iteration 0, the last completed"), std::string::npos) << log;
  ASSERT_TRUE(std::filesystem::exists(run / "checkpoint.pt"));
  const std::string checkpoint = text_of(run / "checkpoint.pt");
  EXPECT_NO_THROW(mimic::verify_zip(checkpoint));

  // Resumed, then SIGINT and SIGTERM back to back (two kinds, so that neither merges into the
  // other): the second exits at once, 130, and the checkpoint is the one that was there.
  const pid_t again = start({"train", "--resume", "-o", run.string()}, dir / "second.log");
  ASSERT_TRUE(wait_for_text(dir / "second.log", "resuming at iteration 0", 120)) << text_of(dir / "second.log");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ::kill(again, SIGINT);
  ::kill(again, SIGTERM);
  const std::optional<int> second = wait_exit(again, 60);
  ASSERT_TRUE(second.has_value()) << text_of(dir / "second.log");
  EXPECT_EQ(*second, 130) << text_of(dir / "second.log");
  EXPECT_NE(text_of(dir / "second.log").find("second stop request: exiting at once"), std::string::npos) << text_of(dir / "second.log");
  EXPECT_EQ(text_of(run / "checkpoint.pt"), checkpoint);
}

// `mimic imitate` stopped while it trains saves, exits 130 like an interrupted shell command, and
// makes none of what follows training (model, evaluation, video): a script that runs it stops
// there instead of going on with a run that did not finish.
TEST(TrainSignals, AStoppedImitateExits130AndMakesNoModel) {
  const auto dir = mimic::test::temp_dir("imitate_signals");
  mimic::save_clip(mimic::builtin_jumping_jack(), dir / "jack.mclip");
  const auto run = dir / "run";
  const pid_t pid = start({"imitate", (dir / "jack.mclip").string(), "-o", run.string(), "--samples", "100000000", "--threads", "1"},
                          dir / "imitate.log");
  ASSERT_TRUE(wait_for_text(dir / "imitate.log", "iterations of 4096 samples", 120)) << text_of(dir / "imitate.log");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ::kill(pid, SIGINT);
  const std::optional<int> status = wait_exit(pid, 60);
  ASSERT_TRUE(status.has_value()) << "still running a minute after SIGINT:\n" << text_of(dir / "imitate.log");
  EXPECT_EQ(*status, 128 + SIGINT) << text_of(dir / "imitate.log");
  EXPECT_NE(text_of(dir / "imitate.log").find("saved; `mimic imitate --resume -o "), std::string::npos) << text_of(dir / "imitate.log");
  EXPECT_TRUE(std::filesystem::exists(run / "checkpoint.pt"));
  EXPECT_FALSE(std::filesystem::exists(run / "model"));
  EXPECT_FALSE(std::filesystem::exists(run / "eval.json"));
}
