#include "cli/output_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <vector>

namespace kinema_cli {

namespace {

std::string reason(int error_number) {
  return error_number != 0 ? std::strerror(error_number) : "write error";
}

[[noreturn]] void fail_file(const std::string& path, int error_number) {
  throw OutputError("cannot write " + path + ": " + reason(error_number) + "; nothing was written");
}

[[noreturn]] void fail_stdout(int error_number) {
  throw OutputError("cannot write standard output: " + reason(error_number));
}

std::string directory_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

// The mode the file gets: that of the file it replaces, else what open(2)
// would give a new file (0666 less the umask); mkstemp itself uses 0600.
mode_t mode_for(const std::string& path) {
  struct stat existing;
  if (::stat(path.c_str(), &existing) == 0 && S_ISREG(existing.st_mode)) return existing.st_mode & 07777;
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
}

// 0 when all of text went to fd, else the errno of the failing write.
int write_all(int fd, std::string_view text) {
  const char* data = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    const ssize_t written = ::write(fd, data, left);
    if (written < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    if (written == 0) return EIO;  // no progress: do not loop for ever
    data += written;
    left -= static_cast<std::size_t>(written);
  }
  return 0;
}


// The file a path names: a symbolic link is followed (the link stays a link and its
// target gets the text), as far as its components exist. A link to a file that does not
// exist is refused: made through the link, the file would land wherever the link points
// (a link planted in /tmp by another user), which the kernel's protected_symlinks check
// would not see; /dev/stdout and /dev/fd/N (links to pipes) exist and are followed.
std::string resolved(const std::string& path, const std::string& shown) {
  struct stat existing, link, directory;
  // As the shell's > does, the directory is looked up as written: weakly_canonical would
  // turn "nodir/../x.csv" into "x.csv" without asking whether nodir exists.
  if (::stat(directory_of(path).c_str(), &directory) != 0) fail_file(shown, errno);
  if (::stat(path.c_str(), &existing) != 0) {
    if (errno != ENOENT) fail_file(shown, errno);  // a loop of links, a file as a directory
    if (::lstat(path.c_str(), &link) == 0 && S_ISLNK(link.st_mode)) {
      throw OutputError("cannot write " + shown + ": it is a symbolic link to a file that does not exist; give the "
                        "target's own path, or remove the link; nothing was written");
    }
  }
  std::error_code error;
  const std::filesystem::path target = std::filesystem::weakly_canonical(path, error);
  return error ? path : target.string();
}

// Refuses what the shell's > would refuse: a file without write permission for this
// user (the rename that replaces a file asks only its directory's), a directory. A file
// that is not there yet needs a directory to make it in.
void check_permission(const std::string& path, const std::string& shown) {
  struct stat existing;
  if (::stat(path.c_str(), &existing) == 0) {
    if (S_ISDIR(existing.st_mode)) fail_file(shown, EISDIR);
    if (::faccessat(AT_FDCWD, path.c_str(), W_OK, AT_EACCESS) != 0) fail_file(shown, errno);
    if (!S_ISREG(existing.st_mode)) return;  // a stream is written directly
  }
  if (::faccessat(AT_FDCWD, directory_of(path).c_str(), W_OK | X_OK, AT_EACCESS) != 0) fail_file(shown, errno);
}

// The temporary of the output being written, for a signal that ends the run (Ctrl-C,
// kill, a closed terminal, timeout's SIGALRM, ulimit -t's SIGXCPU, any other whose
// default is to end the process): the handler removes it, so nothing half-written remains,
// then ends the process as the signal would have. A fixed buffer: a handler may only
// call what is async-signal-safe (unlink, raise), not read a std::string.
char removed_on_signal[4096];
volatile std::sig_atomic_t has_removed_on_signal = 0;

extern "C" void remove_temporary_and_reraise(int signal_number) {
  if (has_removed_on_signal) ::unlink(removed_on_signal);
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

void remove_on_signal(const std::string& temporary) {
  if (temporary.size() >= sizeof removed_on_signal) return;  // not in the buffer: left to the destructor
  has_removed_on_signal = 0;
  std::memcpy(removed_on_signal, temporary.c_str(), temporary.size() + 1);
  has_removed_on_signal = 1;
  // Every signal whose default action ends the process, except the ones a fault raises
  // (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTRAP): those are left to the debugger
  // and the sanitizers, whose reports a handler here would replace.
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGALRM, SIGUSR1, SIGUSR2, SIGPIPE, SIGXCPU,
                                  SIGVTALRM, SIGPROF, SIGSYS,
#ifdef SIGPOLL
                                  SIGPOLL,
#endif
#ifdef SIGPWR
                                  SIGPWR,
#endif
#ifdef SIGSTKFLT
                                  SIGSTKFLT,
#endif
                                 }) {
    struct sigaction current {};
    // A signal the caller ignores (nohup, a background job's SIGINT) stays ignored.
    if (::sigaction(signal_number, nullptr, &current) == 0 && current.sa_handler == SIG_IGN) continue;
    struct sigaction action {};
    action.sa_handler = remove_temporary_and_reraise;
    sigemptyset(&action.sa_mask);
    ::sigaction(signal_number, &action, nullptr);
  }
}

void keep_on_signal() { has_removed_on_signal = 0; }

// A character device, FIFO or socket takes the text as it is: nothing to replace.
bool is_stream(const std::string& path) {
  struct stat existing;
  return ::stat(path.c_str(), &existing) == 0 &&
         (S_ISCHR(existing.st_mode) || S_ISFIFO(existing.st_mode) || S_ISSOCK(existing.st_mode));
}

}  // namespace

Output::Output(const std::string& shown_path) : shown_(shown_path) {
  // Past a file size limit (ulimit -f) a write fails with EFBIG and the run ends with
  // its message (status 5), instead of the process being killed mid-file.
  std::signal(SIGXFSZ, SIG_IGN);
  if (shown_path.empty() || shown_path == "-") {
    flush_standard_output();  // anything written before comes first
    fd_ = STDOUT_FILENO;
    shown_ = "standard output";
    return;
  }
  path_ = resolved(shown_path, shown_);
  check_permission(path_, shown_);
  if (is_stream(path_)) {
    fd_ = ::open(path_.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
    if (fd_ < 0) fail_file(shown_, errno);
    owns_fd_ = true;
    return;
  }
  std::string temporary = directory_of(path_) + "/.kinema-XXXXXX";
  std::vector<char> name(temporary.begin(), temporary.end());
  name.push_back('\0');
  fd_ = ::mkstemp(name.data());  // O_CREAT | O_EXCL, in path's directory
  if (fd_ < 0) fail_file(shown_, errno);
  owns_fd_ = true;
  temporary_ = name.data();
  remove_on_signal(temporary_);
  if (::fchmod(fd_, mode_for(path_)) != 0) fail(errno);
}

Output::~Output() {
  if (owns_fd_) ::close(fd_);
  if (!temporary_.empty()) {
    ::unlink(temporary_.c_str());
    keep_on_signal();
  }
}

void Output::fail(int error_number) {
  if (owns_fd_) ::close(fd_);
  owns_fd_ = false;
  if (!temporary_.empty()) {
    ::unlink(temporary_.c_str());
    keep_on_signal();
    temporary_.clear();
    fail_file(shown_, error_number);
  }
  throw OutputError("cannot write " + shown_ + ": " + reason(error_number));
}

void Output::write(std::string_view text) {
  if (const int error_number = write_all(fd_, text); error_number != 0) fail(error_number);
}

void Output::commit() {
  if (!owns_fd_) return;  // standard output: every write went out already
  int error_number = 0;
  // The rename shows every program the whole new file or the old one, never a part.
  // No fsync before it: waiting for the disk took 25 ms for a 15 MB CSV, longer than
  // computing it, for results that can be computed again (ext4's auto_da_alloc
  // writes a file that replaces another by rename out with the rename anyway).
  if (::close(fd_) != 0 && errno != EINTR) error_number = errno;
  owns_fd_ = false;
  if (error_number == 0 && !temporary_.empty() && std::rename(temporary_.c_str(), path_.c_str()) != 0) error_number = errno;
  if (error_number != 0) fail(error_number);
  keep_on_signal();  // renamed: the name is OUT's now (a signal before this found no file to remove)
  temporary_.clear();
}

void check_output(const std::string& path) {
  if (path.empty() || path == "-") return;
  check_permission(resolved(path, path), path);
}

void write_output(const std::string& text, const std::string& path) {
  Output output(path);
  output.write(text);
  output.commit();
}

void flush_standard_output() {
  errno = 0;
  std::cout.flush();
  const bool flushed = std::fflush(stdout) == 0;
  int error_number = errno;
  if (flushed && !std::ferror(stdout) && std::cout) return;
  if (error_number == 0 && ::fcntl(STDOUT_FILENO, F_GETFL) < 0) error_number = errno;  // closed: EBADF
  fail_stdout(error_number);
}

}  // namespace kinema_cli
