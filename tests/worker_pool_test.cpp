// The worker pool: every index once, on a fixed thread, errors passed back to the caller.
#include <gtest/gtest.h>

#include <atomic>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "core/error.hpp"
#include "core/worker_pool.hpp"

using namespace mimic;

TEST(WorkerPool, RunsEveryIndexOnceOnAFixedThreadAndReusesThreads) {
  WorkerPool pool(3);
  EXPECT_EQ(pool.threads(), 3);
  std::mutex m;
  std::map<int, std::thread::id> first, second;
  std::vector<std::atomic<int>> count(20);
  pool.run(20, [&](int i) {
    ++count[static_cast<std::size_t>(i)];
    std::lock_guard lock(m);
    first[i] = std::this_thread::get_id();
  });
  pool.run(20, [&](int i) {
    std::lock_guard lock(m);
    second[i] = std::this_thread::get_id();
  });
  for (int i = 0; i < 20; ++i) EXPECT_EQ(count[static_cast<std::size_t>(i)].load(), 1) << i;
  EXPECT_EQ(first, second);  // index i always on thread i mod 3
  EXPECT_EQ(first[0], std::this_thread::get_id());  // the caller does thread 0's share
  EXPECT_EQ(first[3], first[0]);
  EXPECT_NE(first[1], first[0]);
  pool.run(0, [](int) { FAIL(); });
}

TEST(WorkerPool, PassesTheFirstErrorBackAndStaysUsable) {
  WorkerPool pool(2);
  EXPECT_THROW(pool.run(6, [](int i) {
    if (i == 3) throw std::runtime_error("boom");
  }),
               std::runtime_error);
  std::atomic<int> n{0};
  pool.run(6, [&](int) { ++n; });
  EXPECT_EQ(n.load(), 6);
  EXPECT_THROW(WorkerPool(0), Error);
}
