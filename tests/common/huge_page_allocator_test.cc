#include "common/huge_page_allocator.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <vector>

namespace motif {
namespace {

TEST(HugePageAllocator, LargeBlocksAreTwoMebibyteAlignedAndUsable) {
  std::vector<int16_t, HugePageAllocator<int16_t>> values(3 << 20);  // 6 MiB
  EXPECT_EQ(reinterpret_cast<uintptr_t>(values.data()) % (2u << 20), 0u);
  std::iota(values.begin(), values.end(), int16_t{0});
  EXPECT_EQ(values[12345], static_cast<int16_t>(12345));
  EXPECT_EQ(values.back(), static_cast<int16_t>((3 << 20) - 1));
  values.resize(5 << 20);  // reallocation copies across two mapped blocks
  EXPECT_EQ(values[12345], static_cast<int16_t>(12345));
  EXPECT_EQ(values[(5 << 20) - 1], 0);
}

TEST(HugePageAllocator, SmallBlocksComeFromTheHeap) {
  std::vector<double, HugePageAllocator<double>> values(100, 1.5);
  EXPECT_EQ(values[99], 1.5);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(values.data()) % alignof(double), 0u);
}

}  // namespace
}  // namespace motif
