// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Running a program (the command-line tool) in a child process with bounds on its processor time
// and its address space, and collecting its exit status, signal, output, wall time and peak
// resident memory. The hostile-input tests use it to check that a file cannot make the tool work
// or allocate without bound: a run that exceeds the bound is killed (SIGXCPU/SIGKILL, or a failed
// allocation that the tool reports as "out of memory"), and the test sees it.

#ifndef SOUP_TOPOLOGY_TEST_BOUNDED_RUN_H
#define SOUP_TOPOLOGY_TEST_BOUNDED_RUN_H

#include <chrono>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace soup_test {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool sanitized_build = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
constexpr bool sanitized_build = true;
#else
constexpr bool sanitized_build = false;
#endif
#else
constexpr bool sanitized_build = false;
#endif

struct Bounded_run
{
  int exit_code = -1;        ///< the exit status, or -1 if a signal ended the process
  int signal = 0;            ///< the signal that ended it, or 0
  double wall_seconds = 0;
  double cpu_seconds = 0;    ///< user + system time of the child
  std::size_t peak_rss_mb = 0;
  std::string out, err;      ///< what it wrote on standard output and standard error

  bool exited_normally() const { return signal == 0 && exit_code >= 0; }
};

/// runs `argv` (argv[0] is the program's path) with at most `cpu_seconds` of processor time and
/// `memory_mb` of address space (the address-space bound is not applied in sanitizer builds, whose
/// shadow memory needs terabytes of address space, and the time bound is multiplied by 10 there).
/// `stdin_file`, if not empty, is opened as the child's standard input (else /dev/null).
inline Bounded_run run_bounded(const std::vector<std::string>& argv, double cpu_seconds = 10,
                               std::size_t memory_mb = 2048, const std::string& stdin_file = "")
{
  char out_name[] = "/tmp/soup_topology_bounded_out_XXXXXX";
  char err_name[] = "/tmp/soup_topology_bounded_err_XXXXXX";
  const int out_fd = mkstemp(out_name);
  const int err_fd = mkstemp(err_name);
  if(out_fd < 0 || err_fd < 0) throw std::runtime_error("run_bounded: cannot create temporary files");
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if(pid < 0) throw std::runtime_error("run_bounded: fork failed");
  if(pid == 0) {
    const double cpu = sanitized_build ? 10 * cpu_seconds : cpu_seconds;
    rlimit cpu_limit;
    cpu_limit.rlim_cur = static_cast<rlim_t>(cpu + 1);
    cpu_limit.rlim_max = static_cast<rlim_t>(cpu + 2);
    setrlimit(RLIMIT_CPU, &cpu_limit);
    if(!sanitized_build) {
      rlimit memory_limit;
      memory_limit.rlim_cur = memory_limit.rlim_max = static_cast<rlim_t>(memory_mb) << 20;
      setrlimit(RLIMIT_AS, &memory_limit);
    }
    const int in_fd = open(stdin_file.empty() ? "/dev/null" : stdin_file.c_str(), O_RDONLY);
    if(in_fd >= 0) dup2(in_fd, 0);
    dup2(out_fd, 1);
    dup2(err_fd, 2);
    std::vector<char*> args;
    for(const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  Bounded_run r;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.cpu_seconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                  1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  r.peak_rss_mb = static_cast<std::size_t>(usage.ru_maxrss) / 1024;
  if(WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  else if(WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  auto slurp = [](const char* name) {
    std::ifstream in(name, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  };
  r.out = slurp(out_name);
  r.err = slurp(err_name);
  close(out_fd);
  close(err_fd);
  std::remove(out_name);
  std::remove(err_name);
  return r;
}

} // namespace soup_test

#endif // SOUP_TOPOLOGY_TEST_BOUNDED_RUN_H
