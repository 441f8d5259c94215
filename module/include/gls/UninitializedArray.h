// Vectors whose new elements stay uninitialized on resize, for the large arrays of a cloud's setup that parallel loops
// fill.
#pragma once

#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace gls
{

/// An allocator whose vectors leave new elements of trivial types uninitialized on resize: for large arrays that a
/// parallel loop then writes whole, so that their pages are first touched (and zeroed by the system) by the threads
/// that fill them rather than zeroed twice on one thread (measured at 10M points: 3-4 s of page zeroing on the calling
/// thread in the pyramid's build).
template <typename T>
struct UninitializedAllocator : std::allocator<T>
{
  template <typename U>
  struct rebind
  {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() = default;
  template <typename U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept
  {
  }
  template <typename U>
  void construct(U* p) noexcept
  {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// A vector of trivial elements left uninitialized by resize (UninitializedAllocator): every element must be written
/// before it is read.
template <typename T>
using UninitializedArray = std::vector<T, UninitializedAllocator<T>>;

} // namespace gls
