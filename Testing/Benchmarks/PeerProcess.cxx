#include "PeerProcess.h"

#include <dirent.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace
{

/// utime + stime from a /proc/.../stat file (fields 14 and 15), in seconds; 0 if unreadable.
double statCpuSeconds(const std::string& path)
{
  std::ifstream stat(path);
  std::string all((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
  const auto close = all.rfind(')'); // the command name may hold spaces
  if (close == std::string::npos)
  {
    return 0.0;
  }
  std::istringstream fields(all.substr(close + 2));
  std::string field;
  double ticks = 0.0;
  for (int i = 3; i <= 15 && (fields >> field); ++i) // fields after the name start at 3 (state)
  {
    if (i >= 14)
    {
      ticks += std::atof(field.c_str());
    }
  }
  return ticks / static_cast<double>(sysconf(_SC_CLK_TCK));
}

/// (thread id, CPU seconds) of every thread of a running process.
std::vector<std::pair<int, double>> threadCpuSeconds(pid_t pid)
{
  std::vector<std::pair<int, double>> threads;
  const std::string tasks = "/proc/" + std::to_string(pid) + "/task";
  if (DIR* dir = opendir(tasks.c_str()))
  {
    while (dirent* entry = readdir(dir))
    {
      if (entry->d_name[0] != '.')
      {
        threads.emplace_back(std::atoi(entry->d_name), statCpuSeconds(tasks + "/" + entry->d_name + "/stat"));
      }
    }
    closedir(dir);
  }
  return threads;
}

} // namespace

int PeerRun::busyThreads(int from, int to) const
{
  if (from < 0 || to < 0 || to <= from)
  {
    return 0;
  }
  const double wall = this->lines[to].seconds - this->lines[from].seconds;
  int busy = 0;
  for (const auto& [tid, cpu] : this->lines[to].threadCpuSeconds)
  {
    double before = 0.0;
    for (const auto& [tid0, cpu0] : this->lines[from].threadCpuSeconds)
    {
      before = tid0 == tid ? cpu0 : before;
    }
    busy += cpu - before >= 0.1 * wall ? 1 : 0;
  }
  return busy;
}

int PeerRun::find(const std::string& marker, int from) const
{
  for (int i = std::max(from, 0); i < static_cast<int>(this->lines.size()); ++i)
  {
    if (this->lines[i].text.find(marker) != std::string::npos)
    {
      return i;
    }
  }
  return -1;
}

std::string PeerRun::tail(int count) const
{
  std::string out;
  for (std::size_t i = this->lines.size() > static_cast<std::size_t>(count) ? this->lines.size() - count : 0;
       i < this->lines.size(); ++i)
  {
    out += "    " + this->lines[i].text + "\n";
  }
  return out;
}

ScratchDirectory::ScratchDirectory()
{
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/gls-peer-XXXXXX";
  if (mkdtemp(&pattern[0]))
  {
    this->Path = pattern;
  }
}

ScratchDirectory::~ScratchDirectory()
{
  for (const std::string& f : this->Files)
  {
    std::remove(f.c_str());
  }
  if (!this->Path.empty())
  {
    rmdir(this->Path.c_str());
  }
}

std::string ScratchDirectory::file(const std::string& name)
{
  this->Files.push_back(this->Path + "/" + name);
  return this->Files.back();
}

std::string findOnPath(const std::string& name)
{
  if (name.find('/') != std::string::npos)
  {
    return access(name.c_str(), X_OK) == 0 ? name : "";
  }
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':'))
  {
    const std::string candidate = (dir.empty() ? "." : dir) + "/" + name;
    if (access(candidate.c_str(), X_OK) == 0)
    {
      return candidate;
    }
  }
  return "";
}

PeerRun runPeer(const std::vector<std::string>& argv, const std::vector<std::string>& environment)
{
  PeerRun run;
  if (argv.empty() || findOnPath(argv[0]).empty())
  {
    run.error = (argv.empty() ? std::string("(no command)") : argv[0]) + ": not found on PATH";
    return run;
  }
  int pipeFds[2];
  if (pipe(pipeFds) != 0)
  {
    run.error = std::string("pipe: ") + std::strerror(errno);
    return run;
  }
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0)
  {
    dup2(pipeFds[1], STDOUT_FILENO);
    dup2(pipeFds[1], STDERR_FILENO);
    close(pipeFds[0]);
    close(pipeFds[1]);
    for (const std::string& assignment : environment)
    {
      putenv(const_cast<char*>(assignment.c_str()));
    }
    std::vector<char*> args;
    for (const std::string& a : argv)
    {
      args.push_back(const_cast<char*>(a.c_str()));
    }
    args.push_back(nullptr);
    execvp(args[0], args.data());
    std::fprintf(stderr, "exec %s: %s\n", args[0], std::strerror(errno));
    _exit(127);
  }
  close(pipeFds[1]);
  if (pid < 0)
  {
    close(pipeFds[0]);
    run.error = std::string("fork: ") + std::strerror(errno);
    return run;
  }
  run.started = true;
  FILE* out = fdopen(pipeFds[0], "r");
  char* line = nullptr;
  std::size_t capacity = 0;
  ssize_t length;
  while ((length = getline(&line, &capacity, out)) >= 0)
  {
    while (length > 0 && (line[length - 1] == '\n' || line[length - 1] == '\r'))
    {
      line[--length] = '\0';
    }
    PeerLine l;
    l.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    l.cpuSeconds = statCpuSeconds("/proc/" + std::to_string(pid) + "/stat");
    l.threadCpuSeconds = threadCpuSeconds(pid);
    l.text = line;
    run.lines.push_back(std::move(l));
  }
  std::free(line);
  std::fclose(out);
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.cpuSeconds = usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
    1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  run.exitStatus = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

std::vector<std::string> onCoresLineBuffered(int threads, std::vector<std::string> argv)
{
  argv.insert(argv.begin(), { "stdbuf", "-oL", "-eL" });
  if (threads > 0 && !findOnPath("taskset").empty())
  {
    argv.insert(argv.begin(), { "taskset", "-c", "0-" + std::to_string(threads - 1) });
  }
  return argv;
}
