// Sorting keyed indices by key on several threads, for the setup of large clouds (coincident points, the
// multi-resolution pyramid's order).
#pragma once

#include "gls/UninitializedArray.h"

#include <cstdint>

namespace gls
{

/// A key and the index of what it keys. A trivial type, so that arrays of them can be left uninitialized until a
/// parallel loop fills them (UninitializedArray).
struct KeyedIndex
{
  std::uint64_t key;
  std::uint64_t index;
};

/// An array of keyed indices (UninitializedArray).
using KeyedIndices = UninitializedArray<KeyedIndex>;

/// Sorts `items` by key in increasing order, stably: items of equal keys keep their order in the input. Where the
/// input lists the items in increasing order of index, the result is therefore ordered by (key, index), the same
/// whatever the thread count. A least-significant-digit radix sort on up to `threads` threads (0: every hardware
/// thread) that skips the digits in which no two keys differ; it holds a second array of the items' size while it
/// runs.
void sortByKey(KeyedIndices& items, int threads);

} // namespace gls
