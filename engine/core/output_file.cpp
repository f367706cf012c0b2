#include "core/output_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <system_error>

#include "core/error.hpp"

namespace dda {

namespace {

[[noreturn]] void cannot_write(const std::filesystem::path& path, const std::string& cause) {
  throw Error(msg("cannot write '", path.string(), "': ", cause));
}

// write(2) until every byte is out; false with errno set on failure.
bool write_all(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return false;
    if (n == 0) {
      errno = EIO;
      return false;
    }
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path, std::string_view bytes, Durability durability) {
  std::filesystem::path part = path;
  part += ".part";
  const int fd = ::open(part.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) cannot_write(path, std::strerror(errno));
  const bool written = write_all(fd, bytes) && (durability == Durability::Renamed || ::fsync(fd) == 0);
  const int write_err = errno;
  const bool closed = ::close(fd) == 0;
  const int close_err = errno;
  if (!written || !closed) {
    std::remove(part.c_str());
    cannot_write(path, std::strerror(written ? close_err : write_err));
  }
  std::error_code ec;
  std::filesystem::rename(part, path, ec);
  if (ec) {
    std::remove(part.c_str());
    cannot_write(path, ec.message());
  }
  if (durability == Durability::Synced) {
    std::filesystem::path dir = path.parent_path();
    if (dir.empty()) dir = ".";
    if (const int d = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); d >= 0) {
      ::fsync(d);
      ::close(d);
    }
  }
}

AppendFile::AppendFile(const std::filesystem::path& path, Mode mode) : path_(path) {
  const int flags = O_WRONLY | O_CREAT | O_CLOEXEC | (mode == Mode::Truncate ? O_TRUNC : O_APPEND);
  fd_ = ::open(path.c_str(), flags, 0666);
  if (fd_ < 0) cannot_write(path, std::strerror(errno));
  const off_t end = ::lseek(fd_, 0, SEEK_END);
  size_ = end > 0 ? end : 0;
}

AppendFile::AppendFile(AppendFile&& o) noexcept : fd_(o.fd_), size_(o.size_), path_(std::move(o.path_)) { o.fd_ = -1; }

AppendFile& AppendFile::operator=(AppendFile&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = o.fd_;
    size_ = o.size_;
    path_ = std::move(o.path_);
    o.fd_ = -1;
  }
  return *this;
}

AppendFile::~AppendFile() {
  if (fd_ >= 0) ::close(fd_);
}

void AppendFile::fail(int err) const { cannot_write(path_, std::strerror(err)); }

void AppendFile::append(std::string_view record) {
  if (fd_ < 0) fail(EBADF);
  if (!write_all(fd_, record)) {
    const int err = errno;
    // Part of the record may be out: cut it off, so the file ends on the
    // last complete record (a device like /dev/full has no size to cut).
    if (::ftruncate(fd_, static_cast<off_t>(size_)) == 0) ::lseek(fd_, static_cast<off_t>(size_), SEEK_SET);
    fail(err);
  }
  size_ += static_cast<long long>(record.size());
}

void AppendFile::close() {
  if (fd_ < 0) return;
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail(errno);
}

}  // namespace dda
