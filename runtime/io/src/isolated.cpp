// The child-process runner of isolated.hpp: fork, a pipe for the result, poll with a deadline, waitpid.
#include "isolated.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <thread>

namespace cga::io_detail {

namespace {

// Writes all of [data, data + n) or gives up on the first error (the parent is gone or stopped reading).
bool write_all(int fd, const char* data, std::size_t n) {
  while (n > 0) {
    const ssize_t k = ::write(fd, data, n);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) return false;
    data += k;
    n -= std::size_t(k);
  }
  return true;
}

[[noreturn]] void child_main(int fd, const std::function<std::string()>& work) {
  // A malformed file is an expected input, not a bug of this process to debug: no core dump per crash.
  const rlimit no_core{0, 0};
  ::setrlimit(RLIMIT_CORE, &no_core);
  for (int sig : {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT, SIGTRAP, SIGSYS}) ::signal(sig, SIG_DFL);
  // The parent may have blocked signals in this thread (some applications do, to take them on one thread).
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  std::string result;
  try {
    result = work();
  } catch (...) {
    ::_exit(2);
  }
  // A length first: the parent tells a complete result from one cut short.
  const std::uint64_t n = result.size();
  const bool sent = write_all(fd, reinterpret_cast<const char*>(&n), sizeof n) && write_all(fd, result.data(), result.size());
  ::_exit(sent ? 0 : 3);
}

}  // namespace

std::string signal_name(int sig) {
  if (const char* abbrev = ::sigabbrev_np(sig)) return std::string("SIG") + abbrev;
  return "signal " + std::to_string(sig);
}

ChildOutcome run_in_child(const std::function<std::string()>& work, std::chrono::milliseconds limit) {
  using clock = std::chrono::steady_clock;
  ChildOutcome out;
  int fds[2];
  // Close-on-exec: a process another thread starts meanwhile must not hold the write end (the parent would
  // then never see end of file).
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    out.output = std::string("pipe: ") + std::strerror(errno);
    return out;
  }
  const pid_t pid = ::fork();
  if (pid < 0) {
    out.output = std::string("fork: ") + std::strerror(errno);
    ::close(fds[0]);
    ::close(fds[1]);
    return out;
  }
  if (pid == 0) {
    ::close(fds[0]);
    child_main(fds[1], work);
  }
  ::close(fds[1]);

  // Read while the child writes (a result larger than the pipe's buffer would otherwise block it), until end
  // of file or the deadline.
  const clock::time_point deadline = clock::now() + limit;
  auto left_ms = [&] {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - clock::now()).count();
    return left > 0 ? int(std::min<long long>(left, 1 << 30)) : 0;
  };
  std::string bytes;
  bool timed_out = false;
  char buffer[1 << 16];
  for (;;) {
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, left_ms());
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) {
      timed_out = true;
      break;
    }
    if (ready < 0) break;
    const ssize_t k = ::read(fds[0], buffer, sizeof buffer);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) break;  // end of file: the child has exited (or closed its end)
    bytes.append(buffer, std::size_t(k));
  }
  ::close(fds[0]);

  // End of file comes as the child exits; give it until the deadline to be reaped, then kill it.
  int status = 0;
  bool reaped = false;
  while (!timed_out) {
    const pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid) {
      reaped = true;
      break;
    }
    if (r < 0 && errno != EINTR) break;  // ECHILD: the application reaps children itself (SIGCHLD ignored)
    if (left_ms() == 0) {
      timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  if (timed_out) {
    ::kill(pid, SIGKILL);
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    out.kind = ChildOutcome::Kind::timed_out;
    return out;
  }

  std::uint64_t n = 0;
  const bool complete = bytes.size() >= sizeof n &&
                        (std::memcpy(&n, bytes.data(), sizeof n), bytes.size() - sizeof n == n);
  if (reaped && WIFSIGNALED(status)) {
    out.kind = ChildOutcome::Kind::signaled;
    out.code = WTERMSIG(status);
  } else if (complete && (!reaped || (WIFEXITED(status) && WEXITSTATUS(status) == 0))) {
    out.kind = ChildOutcome::Kind::finished;
    out.output = bytes.substr(sizeof n);
  } else {
    out.kind = ChildOutcome::Kind::exited;
    out.code = reaped && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  return out;
}

}  // namespace cga::io_detail
