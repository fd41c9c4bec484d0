// util::touch_pages and its helpers: mapping pages in ahead of the writer changes nothing a
// program can see — what a vector held stays, new elements are value-initialised as by resize,
// zeros_touched gives zeros — for ranges that start and end inside pages, less than a page, none.
#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <vector>

#include "tsmframe/util/first_touch.hpp"

namespace {

struct Record {
  int id = -1;
  double value = 2.5;
};

TEST(FirstTouch, ResizeKeepsTheContentsAndValueInitialisesTheRest) {
  std::vector<std::int64_t> v(1000);
  std::iota(v.begin(), v.end(), 7);
  tsm::util::resize_touched(v, 3'000'000);  // ~23 MiB: many parts, several threads
  ASSERT_EQ(v.size(), 3'000'000u);
  for (std::int64_t k = 0; k < 1000; ++k) ASSERT_EQ(v[k], k + 7);
  for (std::size_t k = 1000; k < v.size(); ++k) ASSERT_EQ(v[k], 0) << k;

  std::vector<Record> r;
  tsm::util::resize_touched(r, 200'000);
  for (const Record& x : r) {
    ASSERT_EQ(x.id, -1);
    ASSERT_EQ(x.value, 2.5);
  }
  tsm::util::resize_touched(r, 10);  // shrinking: as resize
  EXPECT_EQ(r.size(), 10u);
}

TEST(FirstTouch, EigenVectorsAreSizedAndZeroed) {
  const Eigen::VectorXd z = tsm::util::zeros_touched(1'000'000);
  ASSERT_EQ(z.size(), 1'000'000);
  EXPECT_EQ(z.cwiseAbs().maxCoeff(), 0.0);
  Eigen::VectorXd v = Eigen::VectorXd::Constant(10, 3.0);
  tsm::util::resize_touched(v, 10);  // the same size: kept as it is
  EXPECT_EQ(v.sum(), 30.0);
  tsm::util::resize_touched(v, 500'000);
  EXPECT_EQ(v.size(), 500'000);
}

TEST(FirstTouch, RangesInsideOnePageOrEmptyAreLeftAlone) {
  std::vector<unsigned char> bytes(3 * 4096, 0xab);
  tsm::util::touch_pages(bytes.data() + 1, 100);  // within a page: nothing to map
  tsm::util::touch_pages(bytes.data(), 0);
  for (const unsigned char b : bytes) ASSERT_EQ(b, 0xab);
}

}  // namespace
