// Runs a peer program (CloudCompare, Open3D's Python, meshlabserver) as a process of its own for the benchmarks:
// its output lines time-stamped as they arrive, with the process's CPU time at each, so that a peer's import,
// compute and export phases can be timed apart from its log.
#pragma once

#include <string>
#include <vector>

/// One line the peer printed: when (seconds since the start), its CPU time so far (user + system, all threads) and
/// each thread's (thread id, seconds), and the text.
struct PeerLine
{
  double seconds = 0.0;
  double cpuSeconds = 0.0;
  std::vector<std::pair<int, double>> threadCpuSeconds;
  std::string text;
};

struct PeerRun
{
  bool started = false;    ///< false: the program could not be run at all (see `error`)
  int exitStatus = -1;     ///< the exit status; -1 when killed by a signal
  double seconds = 0.0;    ///< wall time of the whole process
  double cpuSeconds = 0.0; ///< user + system time of the whole process
  std::vector<PeerLine> lines;
  std::string error;

  bool ok() const { return this->started && this->exitStatus == 0; }
  /// The first line containing `marker` at or after line `from`, or -1.
  int find(const std::string& marker, int from = 0) const;
  /// How many threads worked between lines `from` and `to`: those that used at least 10% of a core then.
  int busyThreads(int from, int to) const;
  /// The last `count` lines, for an error message.
  std::string tail(int count = 15) const;
};

/// A fresh directory under $TMPDIR (or /tmp) for the files exchanged with a peer; removed, with the files named
/// through file(), when it goes out of scope. path() is "" if it could not be created.
class ScratchDirectory
{
public:
  ScratchDirectory();
  ~ScratchDirectory();
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  const std::string& path() const { return this->Path; }
  /// path()/name, removed with the directory.
  std::string file(const std::string& name);

private:
  std::string Path;
  std::vector<std::string> Files;
};

/// The full path of `name` found in PATH (or `name` itself when it holds a '/' and is executable), or "".
std::string findOnPath(const std::string& name);

/// Runs argv (argv[0] looked up in PATH) with `environment` ("NAME=value") added to this process's, stdout and
/// stderr merged and read line by line.
PeerRun runPeer(const std::vector<std::string>& argv, const std::vector<std::string>& environment = {});

/// argv prefixed so that the peer runs on `threads` cores (taskset over cores 0..threads-1; nothing when threads <=
/// 0) and writes its stdout line by line (stdbuf -oL: the time stamps need unbuffered lines).
std::vector<std::string> onCoresLineBuffered(int threads, std::vector<std::string> argv);
