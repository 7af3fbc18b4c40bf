#include "radarslam/core/cleanup_on_signal.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <map>
#include <mutex>
#include <thread>

namespace radarslam {
namespace fs = std::filesystem;

namespace {

struct Registry {
  std::mutex mutex;
  std::map<std::uint64_t, fs::path> paths;  // by registration order
  std::uint64_t next_id = 0;
};

// Never destroyed: the cleanup thread may use it while static destructors run at exit.
Registry& registry() {
  static Registry* r = new Registry;
  return *r;
}

int g_pipe[2] = {-1, -1};
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};

void onSignal(int sig) {
  const int saved = errno;
  const unsigned char byte = static_cast<unsigned char>(sig);
  [[maybe_unused]] const ssize_t n = ::write(g_pipe[1], &byte, 1);
  errno = saved;
}

[[noreturn]] void cleanupThenDie(int sig) {
  Registry& r = registry();
  r.mutex.lock();  // held until the process ends: nothing registers (and then creates) after this
  // Other threads may still be writing into a registered directory (the simulator's writers): a
  // file created while remove_all runs makes its final rmdir fail, so try again until the path is
  // gone (each pass removes what is there; the writers are racing a process about to end).
  for (auto it = r.paths.rbegin(); it != r.paths.rend(); ++it) {
    std::error_code ec;
    for (int pass = 0; pass < 1000 && fs::symlink_status(it->second, ec).type() != fs::file_type::not_found;
         ++pass)
      fs::remove_all(it->second, ec);
  }
  std::signal(sig, SIG_DFL);
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, sig);
  pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
  std::raise(sig);  // delivered to this thread: the default action ends the process
  ::_exit(128 + sig);
}

}  // namespace

void installCleanupOnSignal() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (::pipe2(g_pipe, O_CLOEXEC) != 0) return;  // no cleanup, signals keep their default action
    std::thread([] {
      unsigned char byte = 0;
      for (;;) {
        const ssize_t n = ::read(g_pipe[0], &byte, 1);
        if (n == 1) cleanupThenDie(byte);
        if (n < 0 && errno == EINTR) continue;
        return;
      }
    }).detach();
    for (const int sig : kSignals) {
      struct sigaction old {};
      if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
      struct sigaction sa {};
      sa.sa_handler = onSignal;
      sigemptyset(&sa.sa_mask);
      sa.sa_flags = SA_RESTART;
      ::sigaction(sig, &sa, nullptr);
    }
  });
}

TemporaryPath::TemporaryPath(const fs::path& path) {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  id_ = r.next_id++;
  std::error_code ec;  // absolute: a later chdir must not change what is removed
  const fs::path abs = fs::absolute(path, ec);
  r.paths.emplace(id_, ec ? path : abs);
}

TemporaryPath::~TemporaryPath() {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  r.paths.erase(id_);
}

}  // namespace radarslam
