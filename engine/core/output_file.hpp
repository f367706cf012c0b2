// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The one checked way to write an output file (monitor CSV, run log, PNG
// frames and plots, VTU/PVD, result and sweep tables, checkpoints). Every
// write, flush and close is checked; a failure throws dda::Error
//   "cannot write 'PATH': CAUSE"   (e.g. "No space left on device")
// and never leaves half a record behind:
//
//  * whole files (write_file_atomically): written into PATH.part, then
//    renamed over PATH, so a reader sees the old file or the new one;
//  * files that grow record by record (AppendFile: a CSV row, a log line):
//    each record goes out in whole with write(2); a record that cannot be
//    written in full is cut off again (ftruncate), so every record before
//    the failure stays complete and the file ends on a record boundary. A
//    file made (or emptied) for writing whose first record fails is removed:
//    no empty CSV is left on a full disk.
//
// For a new output (the checkpoint writer, say): build the bytes in memory
// and call write_file_atomically, or open an AppendFile and append() one
// record at a time; let the dda::Error reach the caller (the Lua layer turns
// it into a script error with file and line, and `dda run` exits 1).
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace dda {

// Throws dda::Error "cannot write 'PATH': cause" on any failure (the old
// file, if any, is left as it was). Durable: the file is synced before the
// rename and its folder after it, so the new file also survives a crash of
// the machine (checkpoints ask for it; frames and tables need not wait).
// PATH.part is created afresh (O_EXCL|O_NOFOLLOW: whatever was at that
// name, a leftover or a symbolic link, is removed, never written through),
// and a PATH that is not a regular file (a device, a folder, a pipe, or a
// link to one) is refused: the rename would replace it.
enum class Durability { Renamed, Synced };
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes,
                           Durability durability = Durability::Renamed);
inline constexpr std::string_view kPartSuffix = ".part";

// The *.part files a killed run left in `folder` and two levels of folders
// below it (frames/, vtu/, a sweep's run folders), written before `before`
// (files of a writer running now are younger), and symbolic links of that
// name: removed; returns them. `dda run` calls it on its output folder.
std::vector<std::filesystem::path> remove_stray_part_files(const std::filesystem::path& folder,
                                                           std::filesystem::file_time_type before);

class AppendFile {
 public:
  enum class Mode { Truncate, Append };
  AppendFile() = default;
  // Creates (Truncate: empties) the file; throws dda::Error when it cannot.
  AppendFile(const std::filesystem::path& path, Mode mode);
  AppendFile(AppendFile&& o) noexcept;
  AppendFile& operator=(AppendFile&& o) noexcept;
  AppendFile(const AppendFile&) = delete;
  AppendFile& operator=(const AppendFile&) = delete;
  ~AppendFile();  // closes without throwing (call close() to hear of a failure)

  bool is_open() const { return fd_ >= 0; }
  const std::filesystem::path& path() const { return path_; }
  // Writes the record whole or not at all; throws dda::Error on failure (the
  // file then ends with the previous record).
  void append(std::string_view record);
  // Closes the file; throws dda::Error if the system reports a failure.
  void close();

 private:
  [[noreturn]] void fail(int err) const;
  int fd_ = -1;
  long long size_ = 0;       // bytes of complete records
  bool empty_file_ = false;  // a regular file this object emptied or made, with no record yet
  std::filesystem::path path_;
};

}  // namespace dda
