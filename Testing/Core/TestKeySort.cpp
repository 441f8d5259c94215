// sortByKey (gls/KeySort.h) against std::stable_sort by key: keys of many widths (digits skipped or not),
// repeated keys (their order in the input kept), one thread and several, below and above the parallel threshold.
#include "gls/KeySort.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace
{

using KeyPair = std::pair<std::uint64_t, std::uint64_t>;

/// The items as (key, index) pairs, for comparisons.
std::vector<KeyPair> asPairs(const gls::KeyedIndices& items)
{
  std::vector<KeyPair> pairs(items.size());
  for (std::size_t i = 0; i < items.size(); ++i)
  {
    pairs[i] = { items[i].key, items[i].index };
  }
  return pairs;
}

/// The pairs as keyed indices.
gls::KeyedIndices asItems(const std::vector<KeyPair>& pairs)
{
  gls::KeyedIndices items(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i)
  {
    items[i] = { pairs[i].first, pairs[i].second };
  }
  return items;
}

/// n pairs of keys drawn in [0, 2^bits) (`bits` = 64: any key) with the given low bits cleared, shifted left by
/// `shift`, indices in a shuffled order (so the stable order is not the order of the indices).
std::vector<KeyPair> randomPairs(std::size_t n, int bits, int shift, std::uint64_t seed)
{
  std::mt19937_64 rng(seed);
  std::vector<KeyPair> pairs(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    std::uint64_t key = rng();
    if (bits < 64)
    {
      key &= (std::uint64_t(1) << bits) - 1;
    }
    pairs[i] = { key << shift, i };
  }
  std::shuffle(pairs.begin(), pairs.end(), rng);
  return pairs;
}

} // namespace

TEST(KeySort, StableByKeyForAnyThreadCount)
{
  struct Case
  {
    std::size_t n;
    int bits, shift;
  };
  // 64 bits: every digit; 36 bits: a pyramid's Morton keys; 12 and 3 bits: many repeated keys; shifted keys: low
  // digits all equal (skipped); 0 bits: one key for all.
  const Case cases[] = { { 1000, 64, 0 }, { 200000, 64, 0 }, { 200000, 36, 0 }, { 200000, 12, 0 }, { 150001, 3, 0 },
    { 200000, 20, 30 }, { 70000, 0, 0 }, { 1, 64, 0 }, { 0, 64, 0 } };
  std::uint64_t seed = 1;
  for (const Case& c : cases)
  {
    const std::vector<KeyPair> input = randomPairs(c.n, c.bits, c.shift, seed++);
    std::vector<KeyPair> expected = input;
    std::stable_sort(expected.begin(), expected.end(),
      [](const KeyPair& a, const KeyPair& b) { return a.first < b.first; });
    for (int threads : { 1, 2, 3, 5 })
    {
      gls::KeyedIndices sorted = asItems(input);
      gls::sortByKey(sorted, threads);
      EXPECT_TRUE(asPairs(sorted) == expected)
        << c.n << " pairs of " << c.bits << "-bit keys shifted by " << c.shift << ", " << threads << " threads";
    }
  }
}

TEST(KeySort, IncreasingIndicesGiveThePairsOrder)
{
  // The callers' case: indices increasing in the input, so the result is the pairs' lexicographic order.
  std::mt19937_64 rng(99);
  gls::KeyedIndices items(100000);
  for (std::size_t i = 0; i < items.size(); ++i)
  {
    items[i] = { rng() % 1024, i };
  }
  std::vector<KeyPair> expected = asPairs(items);
  std::sort(expected.begin(), expected.end());
  gls::sortByKey(items, 2);
  EXPECT_TRUE(asPairs(items) == expected);
}
