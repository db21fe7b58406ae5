#include "cutaway/core/contained.hpp"

#include <fcntl.h>
#include <malloc.h>
#include <poll.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <new>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "cutaway/core/error.hpp"

namespace cutaway {

namespace {

// Messages between the process that imports, the helper and its workers (one socket,
// SOCK_SEQPACKET, so each message arrives whole). The first byte says what follows.
constexpr char kResult = 'R';       // a worker's reply, in the memfd that comes with it
constexpr char kError = 'E';        // a worker's cutaway::Error: file, place, reason
constexpr char kOutOfMemory = 'M';  // a worker's failed allocation
constexpr char kOther = 'X';        // a worker's other exception: what()
constexpr char kEnded = 'S';        // the helper's word that the worker ended: status, timedOut

std::map<std::string, ContainedParser>& parsers() {
  static std::map<std::string, ContainedParser> registry;
  return registry;
}

std::vector<void (*)()>& warmUps() {
  static std::vector<void (*)()> registry;
  return registry;
}

bool writeAll(int fd, std::string_view bytes) {
  for (std::size_t at = 0; at < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + at, bytes.size() - at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    at += std::size_t(n);
  }
  return true;
}

// Sends one message, with a descriptor when `fd` ≥ 0.
bool sendMessage(int socket, std::string_view bytes, int fd = -1) {
  iovec iov{const_cast<char*>(bytes.data()), bytes.size()};
  msghdr msg{};
  msg.msg_iov = &iov;
  msg.msg_iovlen = 1;
  alignas(cmsghdr) char control[CMSG_SPACE(sizeof(int))] = {};
  if (fd >= 0) {
    msg.msg_control = control;
    msg.msg_controllen = sizeof control;
    cmsghdr* c = CMSG_FIRSTHDR(&msg);
    c->cmsg_level = SOL_SOCKET;
    c->cmsg_type = SCM_RIGHTS;
    c->cmsg_len = CMSG_LEN(sizeof(int));
    std::memcpy(CMSG_DATA(c), &fd, sizeof fd);
  }
  for (;;) {
    const ssize_t n = ::sendmsg(socket, &msg, MSG_NOSIGNAL);
    if (n >= 0) return std::size_t(n) == bytes.size();
    if (errno != EINTR) return false;
  }
}

// Receives one message and the descriptor that came with it (−1: none); false at the end of
// the stream or on an error.
bool receiveMessage(int socket, std::string& bytes, int& fd) {
  fd = -1;
  ssize_t size;
  do size = ::recv(socket, nullptr, 0, MSG_PEEK | MSG_TRUNC);
  while (size < 0 && errno == EINTR);
  if (size <= 0) return false;
  bytes.assign(std::size_t(size), '\0');
  iovec iov{bytes.data(), bytes.size()};
  msghdr msg{};
  msg.msg_iov = &iov;
  msg.msg_iovlen = 1;
  alignas(cmsghdr) char control[CMSG_SPACE(sizeof(int))] = {};
  msg.msg_control = control;
  msg.msg_controllen = sizeof control;
  ssize_t n;
  do n = ::recvmsg(socket, &msg, MSG_CMSG_CLOEXEC);
  while (n < 0 && errno == EINTR);
  if (n != size) return false;
  for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c; c = CMSG_NXTHDR(&msg, c))
    if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_RIGHTS)
      std::memcpy(&fd, CMSG_DATA(c), sizeof fd);
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

struct Request {
  std::string id, arguments;
  double seconds = 0.0;
  std::uint64_t memoryBytes = 0;
};

template <class Archive>
void wireFields(Archive& a, Request& r) {
  a(r.id, r.arguments, r.seconds, r.memoryBytes);
}

// A worker: one parser on one file, its reply sent to the importing process, then gone.
[[noreturn]] void runWorker(int socket, const Request& request) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  // A crash ends it by the signal (not by a handler the program set up).
  for (int s : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(s, SIG_DFL);
  const rlim_t data = rlim_t(dataSegmentBytes() + request.memoryBytes);
  const rlimit limit{data, data};
  ::setrlimit(RLIMIT_DATA, &limit);
  char kind = kResult;
  std::string reply;
  try {
    const auto parser = parsers().find(request.id);
    if (parser == parsers().end()) throw std::logic_error("no parser \"" + request.id + "\"");
    reply = parser->second(request.arguments);
  } catch (const Error& e) {
    // An error's text goes in one message, under the socket's limit: each part cut at 4 KB.
    kind = kError;
    ByteWriter w;
    w(e.file().substr(0, 4096), e.place().substr(0, 4096), e.reason().substr(0, 4096));
    reply = std::move(w.bytes);
  } catch (const std::bad_alloc&) {
    kind = kOutOfMemory;
  } catch (const std::exception& e) {
    kind = kOther;
    ByteWriter w;
    w(std::string(e.what()).substr(0, 4096));
    reply = std::move(w.bytes);
  }
  bool sent = false;
  if (kind == kResult) {
    // The result goes through shared memory, mapped by the importer rather than copied.
    const int memory = ::memfd_create("cutaway-contained", MFD_CLOEXEC);
    sent = memory >= 0 && writeAll(memory, reply) &&
           sendMessage(socket, std::string_view(&kind, 1), memory);
  } else {
    sent = sendMessage(socket, kind + reply);
  }
  // _exit: the program's exit handlers and buffered streams are the program's.
  ::_exit(sent ? 0 : 120);
}

// The helper: forked once, while the program is small, it forks a fresh worker per file
// (so no file sees what an earlier one did), enforces the time limit and reports how each
// worker ended. The program pays for one fork; a worker copies only the helper's pages.
[[noreturn]] void runHelper(int socket) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  std::signal(SIGCHLD, SIG_DFL);  // its workers are waited for, whatever the program set
  for (void (*warmUp)() : warmUps()) {
    try {
      warmUp();
    } catch (...) {
      // Each worker does it again, and reports what fails.
    }
  }
  for (;;) {
    std::string bytes;
    int unused = -1;
    if (!receiveMessage(socket, bytes, unused)) ::_exit(0);  // the program has gone
    Request request;
    ByteReader r(bytes);
    r(request);
    int pipeEnds[2];
    if (::pipe2(pipeEnds, O_CLOEXEC) != 0) ::_exit(121);
    const pid_t worker = ::fork();
    if (worker == 0) {
      ::close(pipeEnds[0]);
      runWorker(socket, request);  // holds the pipe's write end until it ends
    }
    ::close(pipeEnds[1]);
    bool timedOut = false;
    if (worker > 0) {
      const auto deadline = std::chrono::steady_clock::now() +
                            std::chrono::duration<double>(std::max(request.seconds, 0.0));
      for (;;) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) {
          timedOut = true;
          ::kill(worker, SIGKILL);
          break;
        }
        pollfd p{pipeEnds[0], POLLIN, 0};
        const int n = ::poll(&p, 1, int(std::min<long long>(left.count(), 1000)));
        if (n > 0 || (n < 0 && errno != EINTR)) break;
      }
    }
    ::close(pipeEnds[0]);
    int status = 0;
    if (worker < 0) status = 122 << 8;  // as an exit status: the fork failed
    while (worker > 0 && ::waitpid(worker, &status, 0) < 0 && errno == EINTR) {
    }
    ByteWriter w;
    w(kEnded, status, timedOut);
    if (!sendMessage(socket, w.bytes)) ::_exit(0);
  }
}

class Helper {
 public:
  // Runs one request; the messages that came back, the worker's reply first.
  void run(const std::string& file, const std::string& parser, const Request& request,
           std::string& reply, int& replyFd, int& status, bool& timedOut) {
    if (pid_ > 0 && owner_ != ::getpid()) {
      // This process was forked from the one the helper serves (a Python worker pool):
      // sharing its socket, the processes would read each other's replies. The parent's
      // helper is left to it; this process starts its own.
      ::close(socket_);
      pid_ = -1;
    }
    if (pid_ <= 0) start();
    ByteWriter w;
    w(const_cast<Request&>(request));
    if (!sendMessage(socket_, w.bytes)) {
      // The helper has gone since the last file (killed, say): a new one, once.
      stop();
      start();
      if (!sendMessage(socket_, w.bytes)) stopped(file, parser);
    }
    reply.clear();
    replyFd = -1;
    for (;;) {
      std::string bytes;
      int fd = -1;
      if (!receiveMessage(socket_, bytes, fd)) stopped(file, parser);
      if (bytes[0] == kEnded) {
        ByteReader r(std::string_view(bytes).substr(1));
        r(status, timedOut);
        return;
      }
      reply = std::move(bytes);
      replyFd = fd;
    }
  }

  void start() {
    if (pid_ > 0) return;
    int ends[2];
    if (::socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, ends) != 0)
      throw Error("cannot start the importers' helper process (socketpair: " +
                  std::string(std::strerror(errno)) + ")");
    ::malloc_trim(0);  // what the helper need not copy
    const pid_t pid = ::fork();
    if (pid < 0) {
      ::close(ends[0]);
      ::close(ends[1]);
      throw Error("cannot start the importers' helper process (fork: " +
                  std::string(std::strerror(errno)) + ")");
    }
    if (pid == 0) {
      ::close(ends[0]);
      runHelper(ends[1]);
    }
    ::close(ends[1]);
    pid_ = pid;
    owner_ = ::getpid();
    socket_ = ends[0];
  }

 private:
  void stop() {
    ::close(socket_);
    ::kill(pid_, SIGKILL);
    while (::waitpid(pid_, nullptr, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
  }
  [[noreturn]] void stopped(const std::string& file, const std::string& parser) {
    stop();
    throw Error(file, "", "the helper process running " + parser + " stopped");
  }
  pid_t pid_ = -1, owner_ = -1;  // the helper, and the process it serves
  int socket_ = -1;
};

double positiveNumber(const char* variable, double max) {
  const char* text = std::getenv(variable);
  if (!text) return 0.0;
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !(v > 0.0) || v > max)
    throw Error(variable, "",
                std::string("the environment variable ") + variable + " must be a number in (0, " +
                    std::to_string(int(max)) + "], not " + quote(text));
  return v;
}

std::mutex& helperMutex() {
  static std::mutex mutex;  // one helper, one request at a time
  return mutex;
}

Helper& helper() {
  static Helper helper;
  return helper;
}

}  // namespace

bool registerContainedParser(const std::string& id, ContainedParser parser) {
  return parsers().emplace(id, parser).second;
}

bool registerContainedWarmUp(void (*warmUp)()) {
  warmUps().push_back(warmUp);
  return true;
}

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
  if (!text || std::string_view(text) == "1") return true;
  if (std::string_view(text) == "0") return false;
  throw Error(
      "CUTAWAY_IMPORT_CONTAINED", "",
      std::string("the environment variable CUTAWAY_IMPORT_CONTAINED must be 0 or 1, not ") +
          quote(text));
}

void startContainedHelper() {
  try {
    if (!importsContained()) return;
  } catch (const Error&) {
    return;  // said by the first import
  }
  const std::lock_guard lock(helperMutex());
  try {
    helper().start();
  } catch (const Error&) {
    // The first contained call tries again, and says why it cannot.
  }
}

ContainedReply runContained(const std::string& file, const std::string& parser,
                            const std::string& id, const std::string& arguments,
                            const ContainmentLimits& limits) {
  std::string reply;
  int replyFd = -1, status = 0;
  bool timedOut = false;
  {
    const std::lock_guard lock(helperMutex());
    helper().run(file, parser, Request{id, arguments, limits.seconds, limits.memoryBytes}, reply,
                 replyFd, status, timedOut);
  }
  struct Closer {
    int fd;
    ~Closer() {
      if (fd >= 0) ::close(fd);
    }
  } closer{replyFd};

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
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || reply.empty())
    throw Error(
        file, "",
        prefix + "crashed on this file (exit status " + std::to_string(WEXITSTATUS(status)) + ")");
  ByteReader r(std::string_view(reply).substr(1));
  switch (reply[0]) {
    case kResult: {
      struct stat st {};
      if (replyFd < 0 || ::fstat(replyFd, &st) != 0)
        throw Error(file, "", prefix + "handed back no result");
      if (st.st_size == 0) return ContainedReply(nullptr, 0);
      void* mapped = ::mmap(nullptr, std::size_t(st.st_size), PROT_READ, MAP_PRIVATE | MAP_POPULATE,
                            replyFd, 0);
      if (mapped == MAP_FAILED)
        throw Error(file, "", prefix + "'s result cannot be mapped: " + std::strerror(errno));
      return ContainedReply(static_cast<const char*>(mapped), std::size_t(st.st_size));
    }
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
