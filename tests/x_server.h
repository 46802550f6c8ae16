// An X server of the test's own, for window tests. Xvfb is started with
// -displayfd: the server itself takes the first free display number under
// its lock file and writes it back once it accepts connections, so tests
// running at once never pick the same display (xvfb-run -a checks for a
// free number and starts the server later, and two of them can race for
// one). The server is stopped when the object goes.
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

namespace bounce::test_support {

class x_server {
 public:
  // `log_path`: where Xvfb's own messages go (quoted in error()).
  explicit x_server(const std::string& log_path) : log_path_(log_path) {
    int fds[2];
    if (pipe(fds) != 0) {
      error_ = "pipe() failed";
      return;
    }
    pid_ = fork();
    if (pid_ == 0) {
      close(fds[0]);
      const int log = open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (log >= 0) {
        dup2(log, 1);
        dup2(log, 2);
      }
      const std::string fd = std::to_string(fds[1]);
      execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1280x1024x24", "-nolisten", "tcp",
             "-noreset", static_cast<char*>(nullptr));
      _exit(127);
    }
    close(fds[1]);
    if (pid_ < 0) {
      close(fds[0]);
      error_ = "fork() failed";
      return;
    }
    // The display number and a newline, once the server is ready.
    std::string number;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline) {
      pollfd p{fds[0], POLLIN, 0};
      if (poll(&p, 1, 200) <= 0) continue;
      char c = 0;
      if (read(fds[0], &c, 1) != 1) break;  // the server ended before it was ready
      if (c == '\n') break;
      number += c;
    }
    close(fds[0]);
    if (number.empty()) {
      error_ = "Xvfb did not start (no display number within 60 s); it said:\n" + log();
      stop();
      return;
    }
    display_ = ":" + number;
  }
  ~x_server() { stop(); }
  x_server(const x_server&) = delete;
  x_server& operator=(const x_server&) = delete;

  bool ok() const { return !display_.empty(); }
  const std::string& error() const { return error_; }
  // ":N", for DISPLAY.
  const std::string& display() const { return display_; }
  // What Xvfb printed so far.
  std::string log() const {
    std::ifstream in(log_path_);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }

 private:
  void stop() {
    if (pid_ <= 0) return;
    kill(pid_, SIGTERM);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
  }

  std::string log_path_, display_, error_;
  pid_t pid_ = -1;
};

// Whether Xvfb can be run at all (third_party/install-deps.sh installs it).
inline bool have_xvfb() {
  return std::system("command -v Xvfb >/dev/null 2>&1") == 0;
}

}  // namespace bounce::test_support
