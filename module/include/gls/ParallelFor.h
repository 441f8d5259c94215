// A small thread pool-free parallel loop: the range is cut into fixed chunks that threads take in turn; the calling
// thread works too and is the only one that reports progress, so a VTK filter can forward it to UpdateProgress.
// Results are deterministic as long as each index writes only its own outputs (true for every engine here).
#pragma once

#include <cstddef>
#include <functional>

namespace gls
{

/// Progress callback: receives the fraction done in [0, 1]; returns true to request an abort.
using ProgressCallback = std::function<bool(double)>;

struct ParallelOptions
{
  int threads = 0;             ///< 0 = std::thread::hardware_concurrency()
  std::size_t chunk = 256;     ///< indices per chunk
  ProgressCallback progress;   ///< optional; called from the calling thread only
};

/// The options of one stage of a longer run: the same threads and chunk, progress mapped to [begin, end] of the
/// caller's (no progress when the caller has none). The caller's options must outlive the result.
ParallelOptions progressStage(const ParallelOptions& parallel, double begin, double end);

/// Number of threads a loop with these options will use (at least 1).
int resolveThreadCount(int requested);

/// Runs body(begin, end, threadIndex) over [0, n) in chunks. threadIndex is in [0, resolveThreadCount(threads)).
/// Returns false if the progress callback asked to abort (remaining chunks are then skipped).
bool parallelFor(std::size_t n, const ParallelOptions& options,
  const std::function<void(std::size_t, std::size_t, int)>& body);

} // namespace gls
