// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "core/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
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

// The target's kind, as a reason to refuse it ("a folder"), or nullptr when
// it is absent or a regular file (a symbolic link is judged by what it
// points to: the rename replaces the link, never what it points to).
const char* refused_target(const std::filesystem::path& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || S_ISREG(st.st_mode)) return nullptr;
  if (S_ISDIR(st.st_mode)) return "it is a folder";
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "it is a device, not a regular file";
  if (S_ISFIFO(st.st_mode)) return "it is a pipe (FIFO), not a regular file";
  if (S_ISSOCK(st.st_mode)) return "it is a socket, not a regular file";
  return "it is not a regular file";
}

// PATH.part, created afresh for this write: O_EXCL|O_NOFOLLOW, so that
// nothing already at that name (the leftover of a killed run, a symbolic
// link planted there, a device) is written through. What is there is
// removed first (unlink removes a link, never what it points to); if
// something is put back before the create, the write fails.
int create_part_file(const std::filesystem::path& part) {
  const int flags = O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC;
  int fd = ::open(part.c_str(), flags, 0666);
  if (fd < 0 && errno == EEXIST && ::unlink(part.c_str()) == 0) fd = ::open(part.c_str(), flags, 0666);
  return fd;
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path, std::string_view bytes, Durability durability) {
  if (const char* why = refused_target(path)) cannot_write(path, why);
  std::filesystem::path part = path;
  part += kPartSuffix;
  const int fd = create_part_file(part);
  if (fd < 0) cannot_write(path, std::strerror(errno));
  const bool written = write_all(fd, bytes) && (durability == Durability::Renamed || ::fsync(fd) == 0);
  const int write_err = errno;
  const bool closed = ::close(fd) == 0;
  const int close_err = errno;
  if (!written || !closed) {
    ::unlink(part.c_str());
    cannot_write(path, std::strerror(written ? close_err : write_err));
  }
  std::error_code ec;
  std::filesystem::rename(part, path, ec);
  if (ec) {
    ::unlink(part.c_str());
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

std::vector<std::filesystem::path> remove_stray_part_files(const std::filesystem::path& folder,
                                                           std::filesystem::file_time_type before) {
  namespace fs = std::filesystem;
  std::vector<fs::path> removed;
  std::error_code ec;
  fs::recursive_directory_iterator it(folder, fs::directory_options::skip_permission_denied, ec), end;
  for (; !ec && it != end; it.increment(ec)) {
    if (it.depth() >= 2) it.disable_recursion_pending();  // out/, out/frames/, out/vtu/ and the like
    const fs::path& p = it->path();
    const std::string name = p.filename().string();
    if (name.size() <= kPartSuffix.size() || !name.ends_with(kPartSuffix)) continue;
    std::error_code e;
    if (!it->is_symlink(e) && !it->is_regular_file(e)) continue;
    if (it->is_regular_file(e) && !it->is_symlink(e) && fs::last_write_time(p, e) >= before) continue;
    if (fs::remove(p, e)) removed.push_back(p);
  }
  return removed;
}

AppendFile::AppendFile(const std::filesystem::path& path, Mode mode) : path_(path) {
  const int flags = O_WRONLY | O_CREAT | O_CLOEXEC | (mode == Mode::Truncate ? O_TRUNC : O_APPEND);
  fd_ = ::open(path.c_str(), flags, 0666);
  if (fd_ < 0) cannot_write(path, std::strerror(errno));
  const off_t end = ::lseek(fd_, 0, SEEK_END);
  size_ = end > 0 ? end : 0;
  struct stat st {};
  empty_file_ = mode == Mode::Truncate && ::fstat(fd_, &st) == 0 && S_ISREG(st.st_mode);
}

AppendFile::AppendFile(AppendFile&& o) noexcept
    : fd_(o.fd_), size_(o.size_), empty_file_(o.empty_file_), path_(std::move(o.path_)) {
  o.fd_ = -1;
}

AppendFile& AppendFile::operator=(AppendFile&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = o.fd_;
    size_ = o.size_;
    empty_file_ = o.empty_file_;
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
    // Not even the first record (a CSV's header) went out: no empty file
    // is left behind to look like a result. Later appends fail too.
    if (size_ == 0 && empty_file_) {
      ::unlink(path_.c_str());
      ::close(fd_);
      fd_ = -1;
    }
    fail(err);
  }
  size_ += static_cast<long long>(record.size());
  empty_file_ = false;
}

void AppendFile::close() {
  if (fd_ < 0) return;
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail(errno);
}

}  // namespace dda
