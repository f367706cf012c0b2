// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "world/checkpoint.hpp"

#include <zlib.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

#include "core/archive.hpp"
#include "core/error.hpp"
#include "core/output_file.hpp"
#include "world/stepper.hpp"

namespace dda {

template <class Archive>
void World::fields(Archive& ar) {
  s_.fields(ar);
  stepper_->fields(ar, s_);
}

namespace {

constexpr std::array<char, 8> kMagic{'D', 'D', 'A', '-', 'C', 'K', 'P', 'T'};
constexpr std::uint32_t kByteOrderMark = 0x01020304;
constexpr std::size_t kHeaderBytes = kCheckpointHeaderBytes;

std::uint32_t crc(std::string_view bytes) {
  return static_cast<std::uint32_t>(
      crc32_z(0, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<z_size_t>(bytes.size())));
}

struct Header {
  std::array<char, 8> magic = kMagic;
  std::uint32_t format = kCheckpointFormat;
  std::uint32_t byte_order = kByteOrderMark;
  std::uint64_t payload_bytes = 0;
  std::uint32_t payload_crc = 0;
  std::uint32_t header_crc = 0;
};
static_assert(sizeof(Header) == kHeaderBytes);

}  // namespace

std::string checkpoint_bytes(const World& world, std::string_view extra) {
  ArchiveWriter ar;
  ar.section("world");
  ar(world);
  ar.section("extra");
  ar(std::string(extra));
  ar.section("end");
  return checkpoint_file(ar.bytes());
}

std::string checkpoint_file(std::string_view payload) {
  Header h;
  h.payload_bytes = payload.size();
  h.payload_crc = crc(payload);
  h.header_crc = crc(std::string_view(reinterpret_cast<const char*>(&h), kHeaderBytes - 4));
  std::string out(reinterpret_cast<const char*>(&h), kHeaderBytes);
  out += payload;
  return out;
}

Checkpoint checkpoint_from_bytes(std::string_view bytes, const std::string& what) {
  Header h;
  const bool has_magic = bytes.size() >= kMagic.size() && std::equal(kMagic.begin(), kMagic.end(), bytes.begin());
  if (!has_magic) {
    const bool magic_start =
        !bytes.empty() && bytes.size() < kMagic.size() && std::equal(bytes.begin(), bytes.end(), kMagic.begin());
    throw Error(magic_start ? msg(what, " is truncated: ", bytes.size(), " bytes, not even its header")
                            : msg(what, " is not a dda checkpoint (it does not start with \"DDA-CKPT\")"));
  }
  if (bytes.size() < kHeaderBytes)
    throw Error(msg(what, " is truncated: ", bytes.size(), " bytes, less than its ", kHeaderBytes, "-byte header"));
  std::memcpy(&h, bytes.data(), kHeaderBytes);
  if (crc(bytes.substr(0, kHeaderBytes - 4)) != h.header_crc)
    throw Error(msg(what, " is damaged: its header's checksum does not match"));
  if (h.byte_order != kByteOrderMark)
    throw Error(msg(what, " was written on a machine of the other byte order; continue it there"));
  if (h.format > kCheckpointFormat)
    throw Error(msg(what, " has format ", h.format, ", written by a newer dda; this dda reads format ",
                    kCheckpointFormat, ": continue it with the dda that wrote it"));
  if (h.format < kCheckpointFormat)
    throw Error(msg(what, " has format ", h.format, ", written by an older dda; this dda reads format ",
                    kCheckpointFormat, " only: continue it with the dda that wrote it, or rerun to make a new one"));
  const std::size_t have = bytes.size() - kHeaderBytes;
  if (have < h.payload_bytes)
    throw Error(msg(what, " is truncated: ", bytes.size(), " bytes of ", kHeaderBytes + h.payload_bytes,
                    " (was it copied or written completely?)"));
  if (have > h.payload_bytes) throw Error(msg(what, " is damaged: ", have - h.payload_bytes, " bytes after its end"));
  const std::string_view payload = bytes.substr(kHeaderBytes);
  if (crc(payload) != h.payload_crc) throw Error(msg(what, " is damaged: its checksum does not match its contents"));

  Checkpoint c;
  ArchiveReader ar(payload, what);
  ar.section("world");
  ar(c.world);
  ar.section("extra");
  ar(c.extra);
  ar.section("end");
  if (!ar.at_end()) throw Error(msg(what, " is damaged: ", ar.left(), " bytes after its last part"));
  return c;
}

void save_checkpoint(const World& world, const std::filesystem::path& path, std::string_view extra) {
  write_file_atomically(path, checkpoint_bytes(world, extra), Durability::Synced);
}

Checkpoint load_checkpoint(const std::filesystem::path& path) {
  const std::string what = msg("checkpoint '", path.string(), "'");
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(msg("cannot read ", what, ": it is a folder"));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(msg("cannot read ", what, ": ", std::strerror(errno)));
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw Error(msg("cannot read ", what, ": ", std::strerror(errno)));
  return checkpoint_from_bytes(bytes, what);
}

}  // namespace dda
