// Running a function in a child process (POSIX fork) so that a crash, a hang or a runaway allocation in it
// cannot take the calling process down: the loader runs Assimp's parsers there (see loader.hpp). The child
// sends its result back as bytes over a pipe; the parent learns how the child ended.
#pragma once

#include <chrono>
#include <functional>
#include <string>

namespace cga::io_detail {

struct ChildOutcome {
  enum class Kind {
    finished,   // exited with status 0 after sending all of its result: `output` holds it
    signaled,   // died by signal `code` (SIGSEGV in a parser, SIGKILL from the kernel's OOM killer, ...)
    exited,     // exited with status `code` without a complete result (e.g. a sanitizer's report)
    timed_out,  // still running at the limit: killed
    failed,     // no child could be started (fork or pipe failed; `output` says why)
  };
  Kind kind = Kind::failed;
  int code = 0;
  std::string output;
};

// Runs work() in a forked child and returns the bytes it returned. The child leaves by _exit, so nothing
// of the parent's (atexit handlers, static destructors, stdio buffers) runs twice; it restores the default
// action of the crash signals so that it dies by them (handlers inherited from a test framework or a crash
// reporter would run on a broken heap), and writes no core file. An exception escaping work() ends the child
// with status 2. After `limit` the child is killed (SIGKILL). From a multithreaded caller the child has only
// the calling thread: glibc's fork leaves malloc usable, but a lock that another thread held at the fork stays
// held in the child, which would then wait until the limit.
ChildOutcome run_in_child(const std::function<std::string()>& work, std::chrono::milliseconds limit);

// "SIGSEGV" for SIGSEGV, "signal 42" for one without a name.
std::string signal_name(int sig);

}  // namespace cga::io_detail
