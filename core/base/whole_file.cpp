#include "base/whole_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace bounce {

namespace {
std::atomic<unsigned> next_temporary{0};
}  // namespace

std::string system_reason(const char* fallback) {
  return errno != 0 ? std::string(std::strerror(errno)) : std::string(fallback);
}

bool write_bytes(const std::string& file, const std::string& bytes, std::string& reason) {
  errno = 0;
  std::FILE* f = std::fopen(file.c_str(), "wb");
  if (!f) {
    reason = "cannot open for writing: " + system_reason("unknown reason");
    return false;
  }
  const bool written = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size() && std::fflush(f) == 0;
  const std::string why = written ? "" : system_reason("short write");
  const bool closed = std::fclose(f) == 0;
  if (!written || !closed) {
    reason = "write failed: " + (written ? system_reason("close failed") : why);
    return false;
  }
  return true;
}

bool write_whole(const std::string& path,
                 const std::function<bool(const std::string& temporary, std::string& error)>& write,
                 std::string& error) {
  namespace fs = std::filesystem;
  // Through a symbolic link, the file it names is replaced, not the link.
  std::error_code resolve_error;
  const fs::path real = fs::weakly_canonical(fs::absolute(path), resolve_error);
  const std::string target = resolve_error ? path : real.string();
  // Named after the target, the process and a counter: two runs, or two
  // outputs of one run, never share one.
  const std::string temporary =
      target + ".partial-" + std::to_string(::getpid()) + "-" + std::to_string(next_temporary++);
  std::string reason;
  errno = 0;
  std::error_code ec;
  bool written = false;
  try {
    written = write(temporary, reason);
  } catch (...) {  // out of memory while encoding, say: nothing left beside the target
    fs::remove(temporary, ec);
    throw;
  }
  if (!written) {
    fs::remove(temporary, ec);
    error = path + ": " + (reason.empty() ? "write failed" : reason);
    return false;
  }
  fs::rename(temporary, target, ec);
  if (ec) {
    error = path + ": cannot put the written file in place: " + ec.message();
    fs::remove(temporary, ec);
    return false;
  }
  return true;
}

bool write_file(const std::string& path, const std::string& bytes, std::string& error) {
  return write_whole(
      path, [&](const std::string& file, std::string& reason) { return write_bytes(file, bytes, reason); }, error);
}

}  // namespace bounce
