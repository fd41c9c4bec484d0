// util::parallel_for_*: every index is visited exactly once, on a team or in a plain loop, with
// one thread or two; parallel_all_dynamic is false exactly when some body fails.
#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <vector>

#include "tsmframe/util/parallel_for.hpp"

namespace {

class ParallelFor : public ::testing::TestWithParam<std::pair<int, bool>> {  // (threads, wants a team)
 protected:
  void SetUp() override { omp_set_num_threads(GetParam().first); }
  void TearDown() override { omp_set_num_threads(omp_get_num_procs()); }
};

TEST_P(ParallelFor, VisitsEveryIndexOnce) {
  const bool wants = GetParam().second;
  for (const int n : {0, 1, 7, 1000}) {
    std::vector<std::atomic<int>> seen(n);
    tsm::util::parallel_for_static(0, n, wants, [&](int i) { seen[i]++; });
    for (int i = 0; i < n; ++i) ASSERT_EQ(seen[i], 1) << "static, n " << n << ", index " << i;
    std::vector<std::atomic<int>> again(n);
    tsm::util::parallel_for_dynamic(0L, static_cast<long>(n), wants, [&](long i) { again[i]++; });
    for (int i = 0; i < n; ++i) ASSERT_EQ(again[i], 1) << "dynamic, n " << n << ", index " << i;
  }
}

TEST_P(ParallelFor, AllIsFalseExactlyWhenABodyFails) {
  const bool wants = GetParam().second;
  EXPECT_TRUE(tsm::util::parallel_all_dynamic(0, 100, wants, [](int) { return true; }));
  EXPECT_TRUE(tsm::util::parallel_all_dynamic(0, 0, wants, [](int) { return false; }));
  for (const int failing : {0, 57, 99})
    EXPECT_FALSE(tsm::util::parallel_all_dynamic(0, 100, wants, [&](int i) { return i != failing; })) << failing;
}

TEST_P(ParallelFor, UsesATeamOnlyWhereWantedAndThreadsAllow) {
  const auto [threads, wants] = GetParam();
  std::atomic<int> largest_team{0};
  tsm::util::parallel_for_static(0, 64, wants, [&](int) {
    int seen = largest_team.load();
    while (omp_get_num_threads() > seen && !largest_team.compare_exchange_weak(seen, omp_get_num_threads())) {}
  });
  EXPECT_EQ(largest_team.load(), wants && threads > 1 ? threads : 1);
  EXPECT_EQ(tsm::util::team_available(wants), wants && threads > 1);
}

INSTANTIATE_TEST_SUITE_P(ThreadsAndWish, ParallelFor,
                         ::testing::Values(std::pair{1, false}, std::pair{1, true}, std::pair{2, false}, std::pair{2, true}));

}  // namespace
