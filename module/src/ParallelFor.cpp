#include "gls/ParallelFor.h"

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace gls
{

int resolveThreadCount(int requested)
{
  if (requested > 0)
  {
    return requested;
  }
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

bool parallelFor(std::size_t n, const ParallelOptions& options,
  const std::function<void(std::size_t, std::size_t, int)>& body)
{
  const std::size_t chunk = std::max<std::size_t>(options.chunk, 1);
  const std::size_t chunkCount = (n + chunk - 1) / chunk;
  const int threads = static_cast<int>(std::min<std::size_t>(
    static_cast<std::size_t>(resolveThreadCount(options.threads)), std::max<std::size_t>(chunkCount, 1)));

  std::atomic<std::size_t> next{ 0 };
  std::atomic<std::size_t> done{ 0 };
  std::atomic<bool> aborted{ false };

  auto work = [&](int threadIndex) {
    for (;;)
    {
      if (aborted.load(std::memory_order_relaxed))
      {
        return;
      }
      const std::size_t c = next.fetch_add(1, std::memory_order_relaxed);
      if (c >= chunkCount)
      {
        return;
      }
      const std::size_t begin = c * chunk;
      body(begin, std::min(n, begin + chunk), threadIndex);
      const std::size_t finished = done.fetch_add(1, std::memory_order_relaxed) + 1;
      if (threadIndex == 0 && options.progress)
      {
        if (options.progress(static_cast<double>(finished) / static_cast<double>(chunkCount)))
        {
          aborted.store(true);
        }
      }
    }
  };

  std::vector<std::thread> helpers;
  helpers.reserve(static_cast<std::size_t>(threads - 1));
  for (int t = 1; t < threads; ++t)
  {
    helpers.emplace_back(work, t);
  }
  work(0);
  for (std::thread& h : helpers)
  {
    h.join();
  }
  if (aborted.load())
  {
    return false;
  }
  if (options.progress)
  {
    options.progress(1.0);
  }
  return true;
}

ParallelOptions progressStage(const ParallelOptions& parallel, double begin, double end)
{
  ParallelOptions o = parallel;
  if (parallel.progress)
  {
    o.progress = [&parallel, begin, end](double f) { return parallel.progress(begin + f * (end - begin)); };
  }
  return o;
}

} // namespace gls
