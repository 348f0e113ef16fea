// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The command-line tool's file safety: output paths checked against the input and each other
// before anything is read, every output written to a private temporary file beside its target
// and renamed over it only once all outputs are complete, temporary files removed on any error
// and on SIGINT, SIGTERM and SIGHUP.

#ifndef SOUP_TOPOLOGY_TOOLS_OUTPUT_FILES_H
#define SOUP_TOPOLOGY_TOOLS_OUTPUT_FILES_H

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <limits.h>
#include <ostream>
#include <random>
#include <stdexcept>
#include <streambuf>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

namespace soup_topology_tool {

// An error about a file the tool writes; the message names the file.
struct File_error : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

// ---------------------------------------------------------------------------------------------
// Temporary files removed on a signal. The handler may only call async-signal-safe functions,
// so the paths live in fixed arrays that are filled while the signals are blocked.

constexpr int max_temporaries = 4;
inline char temporary_paths[max_temporaries][PATH_MAX];
inline volatile std::sig_atomic_t temporary_in_use[max_temporaries];

extern "C" inline void remove_temporaries_and_reraise(int signal_number)
{
  for(int i = 0; i < max_temporaries; ++i)
    if(temporary_in_use[i]) unlink(temporary_paths[i]);
  // SA_RESETHAND restored the default action: the process ends as the signal asks (exit status
  // 128 + n in a shell), which a parent can tell from a normal exit.
  raise(signal_number);
}

inline void install_signal_handlers()
{
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = remove_temporaries_and_reraise;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  for(int s : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction previous;
    // An ignored signal (nohup, a shell's background job) stays ignored.
    if(sigaction(s, nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN) continue;
    sigaction(s, &action, nullptr);
  }
}

// Blocks SIGINT, SIGTERM and SIGHUP for its lifetime, so that a file and its registration are
// created or removed together.
class Signal_block
{
public:
  Signal_block()
  {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    sigaddset(&set, SIGHUP);
    sigprocmask(SIG_BLOCK, &set, &previous_);
  }
  ~Signal_block() { sigprocmask(SIG_SETMASK, &previous_, nullptr); }
  Signal_block(const Signal_block&) = delete;
  Signal_block& operator=(const Signal_block&) = delete;

private:
  sigset_t previous_;
};

// ---------------------------------------------------------------------------------------------
// A stream buffer over a file descriptor that remembers the first error (errno).

class Descriptor_buffer : public std::streambuf
{
public:
  Descriptor_buffer() { setp(buffer_, buffer_ + sizeof buffer_); }
  void attach(int fd) { fd_ = fd; }
  int error() const { return error_; }

protected:
  int_type overflow(int_type c) override
  {
    if(!drain()) return traits_type::eof();
    if(!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }

private:
  bool drain()
  {
    const char* p = pbase();
    while(p < pptr()) {
      const ssize_t n = ::write(fd_, p, static_cast<std::size_t>(pptr() - p));
      if(n < 0) {
        if(errno == EINTR) continue;
        if(!error_) error_ = errno;
        return false;
      }
      p += n;
    }
    setp(buffer_, buffer_ + sizeof buffer_);
    return error_ == 0;
  }
  int fd_ = -1;
  int error_ = 0;
  char buffer_[1 << 16];
};

// ---------------------------------------------------------------------------------------------
// Paths

// The mode a new file gets from open(..., 0666): the umask applied.
inline mode_t default_file_mode()
{
  const mode_t mask = umask(0);
  umask(mask);
  return 0666 & ~mask;
}

// Whether `a` and `b` name the same file: the same device and inode when both exist (hard and
// symbolic links, `./a`), else the same absolute path once the existing part is resolved.
inline bool same_file(const std::string& a, const std::string& b)
{
  struct stat sa, sb;
  const bool a_exists = ::stat(a.c_str(), &sa) == 0, b_exists = ::stat(b.c_str(), &sb) == 0;
  if(a_exists && b_exists) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  if(a_exists != b_exists) return false;
  namespace fs = std::filesystem;
  std::error_code ea, eb;
  const fs::path pa = fs::weakly_canonical(fs::absolute(a), ea), pb = fs::weakly_canonical(fs::absolute(b), eb);
  if(ea || eb) return fs::absolute(a).lexically_normal() == fs::absolute(b).lexically_normal();
  return pa == pb;
}

// Checks, without creating anything, that `target` can be written by a rename into its folder:
// the folder exists and is writable, `target` is a regular file if it exists. Throws File_error naming
// `what` and `target`.
inline void check_writable_target(const std::string& target, const std::string& what)
{
  namespace fs = std::filesystem;
  const fs::path path(target);
  const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
  struct stat s;
  if(::stat(folder.c_str(), &s) != 0 || !S_ISDIR(s.st_mode))
    throw File_error(target + ": the " + what + " folder does not exist");
  if(::access(folder.c_str(), W_OK | X_OK) != 0)
    throw File_error(target + ": cannot write into the " + what + " folder (" + std::strerror(errno) + ")");
  if(::stat(target.c_str(), &s) == 0) {
    if(S_ISDIR(s.st_mode)) throw File_error(target + ": is a directory, not a file");
    // A rename would replace a device, a pipe or a socket (or the link to it) by a file.
    if(!S_ISREG(s.st_mode)) throw File_error(target + ": is not a regular file");
  }
}

// ---------------------------------------------------------------------------------------------
// A temporary file beside `target`, created with O_EXCL and mode 0600 (nobody else can read it
// while it is written), registered for removal on a signal, removed by the destructor unless
// committed. `finish()` flushes, closes and gives it the mode of the existing `target` (or the
// default mode of a new file); `commit()` renames it over `target`.

class Temporary_output
{
public:
  explicit Temporary_output(const std::string& target) : target_(target), stream_(nullptr)
  {
    namespace fs = std::filesystem;
    const fs::path path(target);
    const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
    struct stat s;
    mode_ = (::stat(target.c_str(), &s) == 0) ? (s.st_mode & 07777) : default_file_mode();
    std::random_device random;
    for(int attempt = 0; attempt < 100 && fd_ < 0; ++attempt) {
      const std::string name = (folder / (".soup_topology." + std::to_string(random()) + ".tmp" +
                                          path.extension().string())).string();
      if(name.size() >= PATH_MAX) throw File_error(target + ": the path is too long");
      Signal_block block;
      slot_ = -1;
      for(int i = 0; i < max_temporaries && slot_ < 0; ++i)
        if(!temporary_in_use[i]) slot_ = i;
      if(slot_ < 0) throw std::logic_error("too many temporary files");
      fd_ = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
      if(fd_ < 0) {
        if(errno == EEXIST) continue;
        throw File_error(target + ": cannot create a temporary file beside it (" + std::strerror(errno) + ")");
      }
      std::memcpy(temporary_paths[slot_], name.c_str(), name.size() + 1);
      temporary_in_use[slot_] = 1;
      name_ = name;
    }
    if(fd_ < 0) throw File_error(target + ": cannot create a temporary file beside it");
    buffer_.attach(fd_);
    stream_.rdbuf(&buffer_);
  }
  ~Temporary_output() { discard(); }
  Temporary_output(const Temporary_output&) = delete;
  Temporary_output& operator=(const Temporary_output&) = delete;

  std::ostream& stream() { return stream_; }
  const std::string& target() const { return target_; }

  // Flushes the data to the disk and closes the file; throws File_error on any failure.
  void finish()
  {
    stream_.flush();
    if(!stream_ || buffer_.error()) fail(buffer_.error());
    if(::fchmod(fd_, mode_) != 0) fail(errno);
    if(::fsync(fd_) != 0 && errno != EINVAL) fail(errno);
    const int fd = fd_;
    fd_ = -1;
    if(::close(fd) != 0) fail(errno);
  }

  // Renames the finished file over the target.
  void commit()
  {
    Signal_block block;
    if(std::rename(name_.c_str(), target_.c_str()) != 0) {
      const int e = errno;
      discard();
      throw File_error(target_ + ": cannot replace the file (" + std::strerror(e) + ")");
    }
    temporary_in_use[slot_] = 0;
    slot_ = -1;
  }

private:
  [[noreturn]] void fail(int error)
  {
    throw File_error(target_ + ": cannot write the file (" + (error ? std::strerror(error) : "write failed") + ")");
  }
  void discard()
  {
    if(fd_ >= 0) { ::close(fd_); fd_ = -1; }
    if(slot_ >= 0) {
      Signal_block block;
      ::unlink(name_.c_str());
      temporary_in_use[slot_] = 0;
      slot_ = -1;
    }
  }

  std::string target_, name_;
  mode_t mode_ = 0644;
  int fd_ = -1;
  int slot_ = -1;
  Descriptor_buffer buffer_;
  std::ostream stream_;
};

} // namespace soup_topology_tool

#endif // SOUP_TOPOLOGY_TOOLS_OUTPUT_FILES_H
