#include "cutaway/core/contained.hpp"

#include <fcntl.h>
#include <malloc.h>
#include <poll.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <new>
#include <sstream>

#include "cutaway/core/error.hpp"

namespace cutaway {

namespace {

// What the child hands back, first byte: its result, an Error, or a failed allocation.
constexpr char kResult = 'R', kError = 'E', kOutOfMemory = 'M', kOther = 'X';

bool writeAll(int fd, const std::string& bytes) {
  for (std::size_t at = 0; at < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + at, bytes.size() - at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    at += std::size_t(n);
  }
  return true;
}

// The data segment the process already has (VmData, which RLIMIT_DATA limits: the heap and
// private writable mappings, the sanitizers' shadow included), in bytes.
std::uint64_t dataSegmentBytes() {
  std::ifstream status("/proc/self/status");
  std::string key;
  std::uint64_t kilobytes = 0;
  while (status >> key)
    if (key == "VmData:" && status >> kilobytes) return kilobytes * 1024;
  return 0;
}

[[noreturn]] void runChild(int out, const std::function<std::string()>& work,
                           const ContainmentLimits& limits) {
  // Gone with its parent; a crash ends it by the signal (not by a handler the parent set up).
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  for (int s : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(s, SIG_DFL);
  const rlim_t data = rlim_t(dataSegmentBytes() + limits.memoryBytes);
  const rlimit limit{data, data};
  ::setrlimit(RLIMIT_DATA, &limit);
  char kind = kResult;
  std::string reply;
  try {
    reply = work();
  } catch (const Error& e) {
    kind = kError;
    ByteWriter w;
    w(e.file(), e.place(), e.reason());
    reply = std::move(w.bytes);
  } catch (const std::bad_alloc&) {
    kind = kOutOfMemory;
  } catch (const std::exception& e) {
    kind = kOther;
    ByteWriter w;
    w(std::string(e.what()));
    reply = std::move(w.bytes);
  }
  // _exit: the parent's atexit handlers and stdio buffers are the parent's to run and flush.
  ::_exit(writeAll(out, std::string(1, kind)) && writeAll(out, reply) ? 0 : 120);
}

// Closes a descriptor when the scope ends.
struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

double positiveNumber(const char* variable, double max) {
  const char* text = std::getenv(variable);
  if (!text) return 0.0;
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !(v > 0.0) || v > max)
    throw Error(variable, "",
                "expected a number in (0, " + std::to_string(int(max)) + "], got \"" +
                    std::string(text).substr(0, 40) + "\"");
  return v;
}

}  // namespace

ContainedReply::~ContainedReply() {
  if (data_) ::munmap(const_cast<char*>(data_), size_);
}

ContainmentLimits importLimits() {
  ContainmentLimits limits;
  const std::uint64_t physical =
      std::uint64_t(::sysconf(_SC_PHYS_PAGES)) * std::uint64_t(::sysconf(_SC_PAGE_SIZE));
  limits.memoryBytes = physical / 4 * 3;
  if (const double s = positiveNumber("CUTAWAY_IMPORT_SECONDS", 86400.0)) limits.seconds = s;
  if (const double mb = positiveNumber("CUTAWAY_IMPORT_MEMORY_MB", 1 << 24))
    limits.memoryBytes = std::uint64_t(mb * 1024 * 1024);
  return limits;
}

bool importsContained() {
  const char* text = std::getenv("CUTAWAY_IMPORT_CONTAINED");
  return !text || std::string(text) != "0";
}

ContainedReply runContained(const std::string& file, const std::string& parser,
                            const std::function<std::string()>& work,
                            const ContainmentLimits& limits) {
  const auto failed = [&](const std::string& what) {
    return Error(file, "",
                 "cannot run " + parser + " in a child process (" + what + ": " +
                     std::strerror(errno) + ")");
  };
  Fd reply{::memfd_create("cutaway-contained", MFD_CLOEXEC)};
  if (reply.fd < 0) throw failed("memfd_create");
  int pipeEnds[2];
  if (::pipe2(pipeEnds, O_CLOEXEC) != 0) throw failed("pipe");
  // The child holds the write end until it ends: its closing is the parent's signal.
  Fd ended{pipeEnds[0]}, running{pipeEnds[1]};
  ::malloc_trim(0);
  const pid_t pid = ::fork();
  if (pid < 0) throw failed("fork");
  if (pid == 0) runChild(reply.fd, work, limits);
  ::close(running.fd);
  running.fd = -1;

  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration<double>(std::max(limits.seconds, 0.0));
  bool timedOut = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timedOut = true;
      ::kill(pid, SIGKILL);
      break;
    }
    pollfd p{ended.fd, POLLIN, 0};
    const int n = ::poll(&p, 1, int(std::min<long long>(left.count(), 1000)));
    if (n > 0) break;
    if (n < 0 && errno != EINTR) {
      ::kill(pid, SIGKILL);
      break;
    }
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw failed("waitpid");

  const std::string prefix = parser + " ";
  std::ostringstream seconds;
  seconds << limits.seconds;
  if (timedOut)
    throw Error(file, "",
                prefix + "took longer than " + seconds.str() +
                    " s on this file and was stopped (CUTAWAY_IMPORT_SECONDS)");
  if (WIFSIGNALED(status))
    throw Error(
        file, "",
        prefix + "crashed on this file (" + std::string(::strsignal(WTERMSIG(status))) + ")");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw Error(
        file, "",
        prefix + "crashed on this file (exit status " + std::to_string(WEXITSTATUS(status)) + ")");

  struct stat st {};
  if (::fstat(reply.fd, &st) != 0 || st.st_size < 1) throw failed("reading its reply");
  void* mapped = ::mmap(nullptr, std::size_t(st.st_size), PROT_READ, MAP_PRIVATE, reply.fd, 0);
  if (mapped == MAP_FAILED) throw failed("mapping its reply");
  ContainedReply result(static_cast<const char*>(mapped), std::size_t(st.st_size));
  const char kind = *static_cast<const char*>(mapped);
  ByteReader r(result.bytes());
  switch (kind) {
    case kResult:
      return result;
    case kError: {
      std::string errorFile, place, reason;
      r(errorFile, place, reason);
      throw Error(errorFile, place, reason);
    }
    case kOutOfMemory:
      throw Error(file, "",
                  prefix + "needed more than " + std::to_string(limits.memoryBytes >> 20) +
                      " MB of memory for this file (CUTAWAY_IMPORT_MEMORY_MB)");
    default:
      throw Error(file, "", prefix + "failed on this file: " + r.read<std::string>());
  }
}

}  // namespace cutaway
