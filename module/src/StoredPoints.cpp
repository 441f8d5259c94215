#include "gls/StoredPoints.h"

#include "gls/ParallelFor.h"

#include <atomic>

namespace gls
{

bool admittedAreFloatExact(const double* values, std::size_t n, const unsigned char* admit, int threads)
{
  std::atomic<bool> exact{ true };
  ParallelOptions loop;
  loop.threads = threads;
  loop.chunk = 65536;
  parallelFor(n, loop, [&](std::size_t begin, std::size_t end, int) {
    bool mine = true;
    for (std::size_t i = begin; i < end && mine; ++i)
    {
      mine = !admit[i] ||
        (isFloatExact(values[3 * i]) && isFloatExact(values[3 * i + 1]) && isFloatExact(values[3 * i + 2]));
    }
    if (!mine)
    {
      exact.store(false, std::memory_order_relaxed);
    }
  });
  return exact.load();
}

} // namespace gls
