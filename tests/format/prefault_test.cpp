#include "format/prefault.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstdint>
#include <thread>
#include <vector>

namespace srcodec {
namespace {

long minor_faults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

constexpr size_t kWords = size_t{4} << 20;  // 16 MB of uint32_t

TEST(Prefault, KeepsWhatIsThereAndSparesTheFaults) {
  std::vector<uint32_t> v(kWords / 2);
  for (size_t i = 0; i < v.size(); ++i) v[i] = static_cast<uint32_t>(i * 2654435761u);
  v.reserve(kWords);
  const MemoryRange range = capacity_of(v);
  EXPECT_EQ(range.bytes, v.capacity() * sizeof(uint32_t));
  if (!prefault(range)) GTEST_SKIP() << "this system cannot prefault (MADV_POPULATE_WRITE)";
  for (size_t i = 0; i < v.size(); ++i) ASSERT_EQ(v[i], static_cast<uint32_t>(i * 2654435761u)) << i;
  // Writing the prefaulted half that was never written costs (almost) no faults.
  const long before = minor_faults();
  v.resize(kWords, 7u);
  const long faults = minor_faults() - before;
  EXPECT_LT(faults, static_cast<long>(kWords * sizeof(uint32_t) / 4096 / 10)) << faults << " faults";
}

TEST(Prefault, WhileAnotherThreadWrites) {
  std::vector<uint32_t> v;
  v.reserve(kWords);
  const MemoryRange range = capacity_of(v);
  std::thread mapper([range] { prefault(range); });
  for (size_t i = 0; i < kWords; ++i) v.push_back(static_cast<uint32_t>(i ^ 0x5a5a5a5au));
  mapper.join();
  for (size_t i = 0; i < kWords; ++i) ASSERT_EQ(v[i], static_cast<uint32_t>(i ^ 0x5a5a5a5au)) << i;
}

TEST(Prefault, EmptyUnalignedAndFreedRanges) {
  prefault({});
  const std::vector<char> small(100, 'x');
  prefault({small.data() + 1, 50});  // no whole page inside: nothing to do
  EXPECT_EQ(small[1], 'x');
  MemoryRange freed;
  {
    std::vector<uint32_t> gone(kWords);
    freed = capacity_of(gone);
  }
  prefault(freed);  // may fail (unmapped) or map memory someone else owns: no crash, no byte changed
}

TEST(BackgroundPrefault, MapsWhileTheCallerWritesAndStopsWhenDestroyed) {
  std::vector<uint32_t> v;
  v.reserve(kWords);
  {
    const BackgroundPrefault below({capacity_of(v)}, 2 * kWords * sizeof(uint32_t));
    EXPECT_FALSE(below.running());  // under its threshold: no thread
  }
  {
    const BackgroundPrefault mapping({capacity_of(v)}, 0);
    EXPECT_TRUE(mapping.running());
    for (size_t i = 0; i < kWords; ++i) v.push_back(static_cast<uint32_t>(3 * i));
  }
  for (size_t i = 0; i < kWords; ++i) ASSERT_EQ(v[i], static_cast<uint32_t>(3 * i)) << i;
  // A gigabyte of address space reserved and never used: destroyed at once,
  // it stops after a step or two instead of mapping all of it.
  std::vector<char> huge;
  huge.reserve(size_t{1} << 30);
  const long before = minor_faults();
  { const BackgroundPrefault stopped({capacity_of(huge)}, 0); }
  const long faults = minor_faults() - before;
  EXPECT_LT(faults, 20000) << faults << " faults";  // all of it would be 262144 pages
}

}  // namespace
}  // namespace srcodec
