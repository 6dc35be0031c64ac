#include "core/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <functional>
#include <thread>

namespace virtcom {

namespace {

std::string systemError() { return std::strerror(errno); }

// Writes all of `content` to `fd`, then syncs it. False (errno set) on failure.
bool writeAndSync(int fd, std::string_view content) {
  while (!content.empty()) {
    const ssize_t n = ::write(fd, content.data(), content.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    content.remove_prefix(static_cast<size_t>(n));
  }
  return ::fsync(fd) == 0;
}

}  // namespace

std::string replaceFile(const std::string& path, std::string_view content) {
  const std::string temp = path + ".tmp." + std::to_string(::getpid());
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) return systemError();
  const bool written = writeAndSync(fd, content);
  const std::string writeError = written ? "" : systemError();
  ::close(fd);  // after a successful fsync the data is on the disk whatever close says
  if (!written) {
    ::unlink(temp.c_str());
    return writeError;
  }
  if (::rename(temp.c_str(), path.c_str()) != 0) {
    const std::string why = systemError();
    ::unlink(temp.c_str());
    return why;
  }
  // The rename is an entry of the directory: synced with it. A directory that cannot be opened
  // for reading (unusual permissions) leaves the file replaced, only not yet durable.
  std::filesystem::path dir = std::filesystem::path(path).parent_path();
  if (dir.empty()) dir = ".";
  if (const int dirFd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dirFd >= 0) {
    ::fsync(dirFd);
    ::close(dirFd);
  }
  return "";
}

std::string temporaryName(std::string_view base) {
  return std::string(base) + "." + std::to_string(::getpid()) + "." +
         std::to_string(std::hash<std::thread::id>{}(std::this_thread::get_id()));
}

}  // namespace virtcom
