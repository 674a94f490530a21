#ifndef EVOSLAM_TESTS_PROCESS_TESTING_H_
#define EVOSLAM_TESTS_PROCESS_TESTING_H_

// For tests only: child processes that never outlive the test that started them.

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace evoslam::testing {

// One program run as a child process, its stdout and stderr appended to a log file. It is
// killed (SIGKILL) and reaped when the object goes, so a failed assertion or an exception never
// leaves it running; and it gets SIGKILL from the kernel when the thread that started it dies
// (PR_SET_PDEATHSIG), so even a crashed or timed-out test binary leaves no process behind.
class ChildProcess {
 public:
  using Clock = std::chrono::steady_clock;

  // Starts argv[0] (a path) with the rest as its arguments, in this process's environment with
  // `env` ("NAME=VALUE" entries) set on top. Throws std::runtime_error when it cannot start.
  ChildProcess(const std::vector<std::string>& argv, std::filesystem::path log,
               const std::vector<std::string>& env = {})
      : log_(std::move(log)) {
    if (argv.empty()) throw std::runtime_error("ChildProcess: no program");
    // Everything the child needs is made before fork: between fork and exec a child of a
    // multithreaded process may only make async-signal-safe calls.
    std::vector<std::string> environment = env;
    for (char** e = environ; *e != nullptr; ++e) {
      const std::string entry(*e);
      const std::string name = entry.substr(0, entry.find('='));
      bool overridden = false;
      for (const std::string& mine : env) overridden |= mine.rfind(name + "=", 0) == 0;
      if (!overridden) environment.push_back(entry);
    }
    std::vector<char*> argv_c, env_c;
    for (const std::string& a : argv) argv_c.push_back(const_cast<char*>(a.c_str()));
    argv_c.push_back(nullptr);
    for (const std::string& e : environment) env_c.push_back(const_cast<char*>(e.c_str()));
    env_c.push_back(nullptr);
    const int fd = ::open(log_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd < 0) throw std::runtime_error("cannot open " + log_.string());
    const pid_t parent = ::getpid();
    pid_ = ::fork();
    if (pid_ == 0) {
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (::getppid() != parent) ::_exit(127);  // the parent died before prctl took effect
      sigset_t none;
      sigemptyset(&none);
      ::sigprocmask(SIG_SETMASK, &none, nullptr);
      ::dup2(fd, STDOUT_FILENO);
      ::dup2(fd, STDERR_FILENO);
      ::execve(argv_c[0], argv_c.data(), env_c.data());
      ::_exit(127);
    }
    const int fork_errno = errno;
    ::close(fd);
    if (pid_ < 0) throw std::runtime_error("fork: " + std::string(std::strerror(fork_errno)));
  }

  ~ChildProcess() {
    if (pid_ > 0 && !status_) {
      ::kill(pid_, SIGKILL);  // also ends a stopped process
      int status = 0;
      while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
      }
    }
  }
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  const std::filesystem::path& log_path() const { return log_; }

  // Sends a signal; false when the process has already ended.
  bool Kill(int signal) {
    if (!Alive()) return false;
    return ::kill(pid_, signal) == 0;
  }

  // Whether it still runs (a stopped process counts as running); reaps it when it has ended.
  bool Alive() {
    if (status_) return false;
    int status = 0;
    const pid_t r = ::wait4(pid_, &status, WNOHANG, &usage_);
    if (r == pid_) status_ = status;
    return !status_;
  }

  // Waits until it ends and returns its wait status (as waitpid gives it), or nullopt when it
  // still runs after `timeout`.
  std::optional<int> Wait(Clock::duration timeout) {
    const Clock::time_point until = Clock::now() + timeout;
    while (Alive()) {
      if (Clock::now() >= until) return std::nullopt;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return status_;
  }

  // Its exit code once it ended normally; nullopt while it runs or when a signal ended it.
  std::optional<int> exit_code() {
    if (Alive() || !WIFEXITED(*status_)) return std::nullopt;
    return WEXITSTATUS(*status_);
  }

  // Its peak resident memory in KiB (getrusage's ru_maxrss, which /usr/bin/time -v reports as
  // the maximum resident set size) once it has ended; nullopt while it runs.
  std::optional<long> max_rss_kib() {
    if (Alive()) return std::nullopt;
    return usage_.ru_maxrss;
  }

  // Everything it wrote so far.
  std::string Log() const {
    std::ifstream in(log_, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }

  // How a wait status reads, for failure messages.
  static std::string Describe(int status) {
    if (WIFEXITED(status)) return "exit code " + std::to_string(WEXITSTATUS(status));
    if (WIFSIGNALED(status)) return "killed by signal " + std::to_string(WTERMSIG(status));
    return "wait status " + std::to_string(status);
  }

 private:
  std::filesystem::path log_;
  pid_t pid_ = -1;
  std::optional<int> status_;
  rusage usage_{};
};

}  // namespace evoslam::testing

#endif  // EVOSLAM_TESTS_PROCESS_TESTING_H_
