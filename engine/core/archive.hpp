// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The bytes of a checkpoint (world/checkpoint.hpp): one list of fields per
// type, read and written by the same code (as cereal's serialize). A type
// that carries state from step to step lists its fields in a member
//
//   template <class Archive> void fields(Archive& ar) { ar(a, b, c); }
//
// next to their declarations; adding a field to the state is adding it to
// that list (and raising kCheckpointFormat, world/checkpoint.hpp). Numbers
// are stored as their bytes (bit for bit: a restart continues exactly);
// containers as their size, then their elements. ar.section("name") marks
// where a part starts, so a damaged or mismatched file is named where it
// goes wrong.
//
// Reading treats the bytes as untrusted (anyone can edit a file and
// recompute its checksums): a count that the bytes left cannot hold, at the
// least bytes an element takes in the file, is damage reported before
// anything is allocated, so what a file makes this process allocate stays
// within a few times its size; a flag must be 0 or 1 and an enum one of its
// values (each archived enum declares its last one, `enum_last`, beside it);
// text from the file reaches messages only escaped (printable()). What the
// values mean (indices into the model) each type checks after reading
// (core/load_check.hpp).
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <concepts>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/error.hpp"

namespace dda {

// An archived enum E declares `constexpr E enum_last(E)` beside it (found by
// argument-dependent lookup): its values run from 0 to that one.
template <class E>
concept ArchivedEnum = std::is_enum_v<E> && requires(E e) {
  { enum_last(e) } -> std::same_as<E>;
};

template <class T, class Archive>
concept HasFields = requires(T& t, Archive& ar) {
  t.fields(ar);
};

class ArchiveWriter {
 public:
  static constexpr bool reading = false;

  template <class... T>
  void operator()(const T&... values) {
    (put(values), ...);
  }
  void section(std::string_view name) { put(std::string(name)); }
  const std::string& bytes() const { return bytes_; }

 private:
  void raw(const void* p, std::size_t n) { bytes_.append(static_cast<const char*>(p), n); }

  template <class T>
  void put(const T& v) {
    if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
      raw(&v, sizeof v);
    } else if constexpr (HasFields<T, ArchiveWriter>) {
      const_cast<T&>(v).fields(*this);  // fields() serves both directions; writing reads only
    } else {
      put_container(v);
    }
  }
  template <class Scalar, int R, int C, int O, int MR, int MC>
  void put_container(const Eigen::Matrix<Scalar, R, C, O, MR, MC>& m) {
    if constexpr (R == Eigen::Dynamic || C == Eigen::Dynamic)
      put(std::uint64_t(m.rows())), put(std::uint64_t(m.cols()));
    raw(m.data(), sizeof(Scalar) * m.size());
  }
  template <class T, class A>
  void put_container(const std::vector<T, A>& v) {
    put(std::uint64_t(v.size()));
    if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>)
      raw(v.data(), sizeof(T) * v.size());
    else
      for (const T& e : v) put(e);
  }
  template <class T, std::size_t N>
  void put_container(const std::array<T, N>& a) {
    for (const T& e : a) put(e);
  }
  void put_container(const std::string& s) {
    put(std::uint64_t(s.size()));
    raw(s.data(), s.size());
  }
  template <class T>
  void put_container(const std::optional<T>& o) {
    put(o.has_value());
    if (o) put(*o);
  }
  template <class A, class B>
  void put_container(const std::pair<A, B>& p) {
    put(p.first), put(p.second);
  }

  std::string bytes_;
};

class ArchiveReader {
 public:
  static constexpr bool reading = true;

  // `what` names the bytes in messages ("checkpoint 'run.ckpt'").
  ArchiveReader(std::string_view bytes, std::string what) : bytes_(bytes), what_(std::move(what)) {}

  template <class... T>
  void operator()(T&... values) {
    (get(values), ...);
  }
  void section(std::string_view name) {
    std::string found;
    get(found);
    if (found != name)
      throw Error(msg(what_, " is damaged or was written by another build of dda: expected its part '", name,
                      "' after '", section_, "', found '", printable(found, 40), "'"));
    section_ = name;
  }
  bool at_end() const { return pos_ == bytes_.size(); }
  std::size_t left() const { return bytes_.size() - pos_; }
  const std::string& what() const { return what_; }

 private:
  [[noreturn]] void damaged() const { throw Error(msg(what_, " is damaged: its part '", section_, "' ends early")); }
  template <class... Parts>
  [[noreturn]] void bad_value(const Parts&... parts) const {
    throw Error(msg(what_, " is damaged: its part '", section_, "' holds ", parts...));
  }
  void raw(void* p, std::size_t n) {
    if (n > left()) damaged();
    if (n == 0) return;  // (an empty vector's data() may be null: no memcpy from or to it)
    std::memcpy(p, bytes_.data() + pos_, n);
    pos_ += n;
  }
  // A count of elements of type T, checked against the bytes left at the
  // least bytes one takes in the file (an empty default element's).
  template <class T>
  std::size_t count() {
    static const std::size_t min_bytes = [] {
      if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
        return sizeof(T);
      } else {
        ArchiveWriter w;
        w(T{});
        return std::max<std::size_t>(w.bytes().size(), 1);
      }
    }();
    std::uint64_t n = 0;
    get(n);
    if (n > left() / min_bytes) damaged();
    return static_cast<std::size_t>(n);
  }

  template <class T>
  void get(T& v) {
    if constexpr (std::is_same_v<T, bool>) {
      std::uint8_t b = 0;
      raw(&b, 1);
      if (b > 1) bad_value("a flag of value ", int(b), " (not 0 or 1)");
      v = b != 0;
    } else if constexpr (std::is_enum_v<T>) {
      static_assert(ArchivedEnum<T>, "an archived enum declares enum_last beside it");
      std::underlying_type_t<T> u{};
      raw(&u, sizeof u);
      using Wide = long long;
      if (Wide(u) < 0 || Wide(u) > Wide(enum_last(T{})))
        bad_value("an enum of value ", Wide(u), " (not one of its values)");
      v = static_cast<T>(u);
    } else if constexpr (std::is_arithmetic_v<T>) {
      raw(&v, sizeof v);
    } else if constexpr (HasFields<T, ArchiveReader>) {
      v.fields(*this);
    } else {
      get_container(v);
    }
  }
  template <class Scalar, int R, int C, int O, int MR, int MC>
  void get_container(Eigen::Matrix<Scalar, R, C, O, MR, MC>& m) {
    if constexpr (R == Eigen::Dynamic || C == Eigen::Dynamic) {
      std::uint64_t rows = 0, cols = 0;
      get(rows), get(cols);
      if ((R != Eigen::Dynamic && rows != std::uint64_t(R)) || (C != Eigen::Dynamic && cols != std::uint64_t(C)))
        bad_value("a matrix of ", rows, " × ", cols, " where it has ", R, " × ", C);
      if (rows > left() || cols > left() || (cols != 0 && rows > left() / sizeof(Scalar) / cols)) damaged();
      m.resize(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
    }
    raw(m.data(), sizeof(Scalar) * m.size());
  }
  template <class T, class A>
  void get_container(std::vector<T, A>& v) {
    if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
      v.resize(count<T>());
      raw(v.data(), sizeof(T) * v.size());
    } else {
      v.clear();
      v.resize(count<T>());
      for (T& e : v) get(e);
    }
  }
  template <class T, std::size_t N>
  void get_container(std::array<T, N>& a) {
    for (T& e : a) get(e);
  }
  void get_container(std::string& s) {
    s.resize(count<char>());
    raw(s.data(), s.size());
  }
  template <class T>
  void get_container(std::optional<T>& o) {
    bool has = false;
    get(has);
    o.reset();
    if (has) get(o.emplace());
  }
  template <class A, class B>
  void get_container(std::pair<A, B>& p) {
    get(p.first), get(p.second);
  }

  std::string_view bytes_;
  std::size_t pos_ = 0;
  std::string what_;
  std::string section_ = "header";
};

}  // namespace dda
