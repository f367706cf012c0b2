// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Checks of a state read from a file anyone can edit (a checkpoint, whose
// checksums only catch accidents): every index, count and size against the
// model it belongs to, before anything is built from it. The reader itself
// (core/archive.hpp) bounds counts by the bytes left and checks flags and
// enums; what the values mean, each type checks beside its field list, in a
// `check_loaded(const LoadCheck&, ...)` that a reading fields() calls last.
// A failed check throws dda::Error "<what> is damaged: <detail>".
#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/error.hpp"

namespace dda {

class LoadCheck {
 public:
  explicit LoadCheck(std::string what) : what_(std::move(what)) {}
  const std::string& what() const { return what_; }

  template <class... Detail>
  [[noreturn]] void fail(const Detail&... detail) const {
    throw Error(msg(what_, " is damaged: ", detail...));
  }
  template <class... Detail>
  void require(bool ok, const Detail&... detail) const {
    if (!ok) fail(detail...);
  }
  // i indexes a list of n `things`: "NAME is I, and there are N things" unless 0 ≤ i < n.
  template <class I, class... Name>
  void index(I i, std::size_t n, const char* things, const Name&... name) const {
    static_assert(std::is_integral_v<I>);
    if (!in_range(i, n)) fail(name..., " is ", i, ", and there are ", n, " ", things);
  }
  // As index(), where -1 stands for none.
  template <class I, class... Name>
  void index_or_none(I i, std::size_t n, const char* things, const Name&... name) const {
    if (i != -1) index(i, n, things, name...);
  }
  // A list parallel to another: "NAME has G entries for N things".
  template <class... Name>
  void size(std::size_t got, std::size_t want, const char* things, const Name&... name) const {
    if (got != want) fail(name..., " has ", got, " entries for ", want, " ", things);
  }
  template <class... Name>
  void finite(double v, const Name&... name) const {
    if (!std::isfinite(v)) fail(name..., " is not finite (", v, ")");
  }
  template <class Derived, class... Name>
  void finite(const Eigen::DenseBase<Derived>& v, const Name&... name) const {
    if (!v.allFinite()) fail(name..., " is not finite");
  }
  template <class T, class... Name>
  void all_finite(const std::vector<T>& values, const Name&... name) const {
    for (std::size_t i = 0; i < values.size(); ++i)
      if (!is_finite(values[i])) fail(name..., " ", i, " is not finite");
  }

  template <class I>
  static bool in_range(I i, std::size_t n) {
    if constexpr (std::is_signed_v<I>)
      if (i < 0) return false;
    return static_cast<unsigned long long>(i) < n;
  }

 private:
  static bool is_finite(double v) { return std::isfinite(v); }
  template <class Derived>
  static bool is_finite(const Eigen::DenseBase<Derived>& v) {
    return v.allFinite();
  }
  std::string what_;
};

}  // namespace dda
