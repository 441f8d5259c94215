#include "gls/KeySort.h"

#include "gls/ParallelFor.h"

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

namespace gls
{
namespace
{

/// Bits of a key taken per pass (2,048 buckets: six passes cover 64 bits). Measured on 10M items (2 threads, 64-bit
/// keys): 8 bits 0.31 s, 11 bits 0.28 s, 13 bits 0.30 s; a sort of the (key, index) pairs in two slices and a merge
/// 0.46 s.
constexpr int kDigitBits = 11;
constexpr std::size_t kBuckets = std::size_t(1) << kDigitBits;

/// Below this many items, one thread (the passes' thread starts would cost more than they save).
constexpr std::size_t kParallelItems = 65536;

} // namespace

void sortByKey(KeyedIndices& items, int threads)
{
  const std::size_t n = items.size();
  if (n < 2)
  {
    return;
  }
  // The bits in which some key differs from the first: the digits without any are already in order.
  std::uint64_t varying = 0;
  for (const KeyedIndex& item : items)
  {
    varying |= item.key ^ items[0].key;
  }
  const std::size_t slices = n < kParallelItems ? 1 : static_cast<std::size_t>(resolveThreadCount(threads));
  ParallelOptions bySlice;
  bySlice.threads = static_cast<int>(slices);
  bySlice.chunk = 1;
  const auto sliceBegin = [n, slices](std::size_t s) { return n * s / slices; };

  KeyedIndices scratch(n); // uninitialized: first touched by the passes' threads
  KeyedIndex* from = items.data();
  KeyedIndex* to = scratch.data();
  std::vector<std::array<std::size_t, kBuckets>> counts(slices);
  for (int shift = 0; shift < 64; shift += kDigitBits)
  {
    if (((varying >> shift) & (kBuckets - 1)) == 0)
    {
      continue;
    }
    const auto digit = [shift](const KeyedIndex& item) {
      return static_cast<std::size_t>((item.key >> shift) & (kBuckets - 1));
    };
    parallelFor(slices, bySlice, [&](std::size_t s, std::size_t, int) {
      std::array<std::size_t, kBuckets>& c = counts[s];
      c.fill(0);
      for (std::size_t i = sliceBegin(s); i < sliceBegin(s + 1); ++i)
      {
        ++c[digit(from[i])];
      }
    });
    // Each slice's first place in each bucket: the buckets in order, within a bucket the slices in order (stable).
    std::size_t place = 0;
    for (std::size_t b = 0; b < kBuckets; ++b)
    {
      for (std::size_t s = 0; s < slices; ++s)
      {
        const std::size_t c = counts[s][b];
        counts[s][b] = place;
        place += c;
      }
    }
    parallelFor(slices, bySlice, [&](std::size_t s, std::size_t, int) {
      std::array<std::size_t, kBuckets>& next = counts[s];
      for (std::size_t i = sliceBegin(s); i < sliceBegin(s + 1); ++i)
      {
        to[next[digit(from[i])]++] = from[i];
      }
    });
    std::swap(from, to);
  }
  if (from != items.data())
  {
    ParallelOptions copying;
    copying.threads = static_cast<int>(slices);
    copying.chunk = 1 << 16;
    parallelFor(
      n, copying, [&](std::size_t b, std::size_t e, int) { std::copy(from + b, from + e, items.data() + b); });
  }
}

} // namespace gls
