// Running the mechkin executable from a test: one shared copy (the reliability
// and CLI tests used to carry their own popen and fork runners).
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

namespace mechkin_test {

inline const std::string& MechkinBinary() {
  static const std::string bin = MECHKIN_BINARY;
  return bin;
}

struct CliResult {
  int code = 0;     // the exit code, or 128 + the signal that ended it
  std::string out;  // stdout and stderr together
};

/// `mechkin ARGS` through the shell with `stderr_to` as stderr's redirection ("&1":
/// into the captured output), waited for.
inline CliResult RunCliWithStderr(const std::string& args, const std::string& stderr_to) {
  CliResult r;
  FILE* p = ::popen((MechkinBinary() + " " + args + " 2>" + stderr_to).c_str(), "r");
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int status = ::pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

/// `mechkin ARGS` through the shell (ARGS may redirect), waited for.
inline CliResult RunCli(const std::string& args) { return RunCliWithStderr(args, "&1"); }

/// How a signalled child ended: an exit code of its own, or killed by a signal.
struct SignalledExit {
  bool exited = false;  // it called exit (code); otherwise killed by `signal`
  int code = -1, signal = 0;
};

/// Runs mechkin with `args` (stdout and stderr to /dev/null), sends `sig` after `ms`
/// milliseconds and waits for it.
inline SignalledExit RunAndSignal(const std::vector<std::string>& args, int sig, int ms) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(MechkinBinary().c_str()));
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::signal(SIGINT, SIG_DFL);  // a test run in the background inherits SIGINT ignored
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(ms));
  ::kill(pid, sig);
  int status = 0;
  ::waitpid(pid, &status, 0);
  SignalledExit e;
  e.exited = WIFEXITED(status);
  e.code = e.exited ? WEXITSTATUS(status) : -1;
  e.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  return e;
}

}  // namespace mechkin_test
