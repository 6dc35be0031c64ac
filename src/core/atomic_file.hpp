#pragma once
// Files that are never seen half written: a file the program rewrites while it runs (the retain
// file, the ADS routes file a UDP add route grows) must read whole after a crash or a kill -9 at
// any moment, as the old content or the new, never a mix or a torn end.
#include <string>
#include <string_view>

namespace virtcom {

// Replaces `path` with `content`: written to a temporary file beside it (`path` + ".tmp." + the
// process id), flushed to the disk (fsync), renamed over `path` (atomic on POSIX file systems),
// then the directory synced so the rename itself survives a power loss. A kill before the rename
// leaves `path` as it was (and the temporary file, which the next replace overwrites). The
// reason on failure (the system's message), "" on success.
std::string replaceFile(const std::string& path, std::string_view content);

// `base` + "." + the process id + "." + a hash of the thread id: a temporary name no other process
// or thread uses at the same time, for the caches' files written beside their place and renamed
// into it (concurrent writers of one entry never share a temporary file).
std::string temporaryName(std::string_view base);

}  // namespace virtcom
