// Outputs written whole or not at all: the content goes to a file beside
// the target (same folder, so the rename cannot cross file systems), which
// is renamed over the target once every write and the close succeeded. A
// failed write leaves the old file as it was; so does a killed run, which
// at worst leaves the partial file beside it.
#pragma once

#include <functional>
#include <string>

namespace bounce {

// Calls `write` with a temporary path beside `path` (`write` creates and
// fills it, returning false with its reason in `error`), then renames it
// over `path`. Returns false with `error` naming `path` and the reason
// (the system's words for it, as strerror gives them).
bool write_whole(const std::string& path,
                 const std::function<bool(const std::string& temporary, std::string& error)>& write,
                 std::string& error);

// Writes `bytes` to `file` (created or truncated), checking every write
// and the close: a full disk is an error, not a short file. Returns false
// with the reason.
bool write_bytes(const std::string& file, const std::string& bytes, std::string& reason);

// `bytes` as the whole of `path`: write_whole with write_bytes.
bool write_file(const std::string& path, const std::string& bytes, std::string& error);

// The system's words for the last failed call (errno), or `fallback`.
std::string system_reason(const char* fallback);

}  // namespace bounce
