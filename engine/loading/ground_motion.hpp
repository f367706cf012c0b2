// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Earthquake ground motion: an accelerogram read from a strong-motion file
// (the USGS/CDMG corrected-accelerogram layout of data/, or a two-column
// time, acceleration CSV), resampled to a time step, baseline-corrected and
// integrated to velocity and displacement. Everything inside is SI (m/s²,
// m/s, m); the units of a file are converted on reading.
//
// Integration is exact for an acceleration piecewise linear between samples:
//   v[i+1] = v[i] + Δt·(a[i] + a[i+1])/2,
//   u[i+1] = u[i] + Δt·v[i] + Δt²·(a[i]/3 + a[i+1]/6).
//
// Baseline correction (the usual practice, Boore 2001 "Effect of baseline
// corrections on displacements and response spectra"): the velocity
// integrated from rest is fitted by least squares with a polynomial
// p(t) = c1·t + … + cn·tⁿ (no constant term: the ground starts at rest), and
// p′(t) is taken off the acceleration. Then the velocity is v − p and the
// displacement u − ∫p, both still zero at t = 0. Order 2 (a linear and a
// quadratic drift of velocity: a constant and a linearly growing offset of
// the acceleration, the signature of a shifted zero line and of tilt) is the
// default; order 0 leaves the record as read.
#include <istream>
#include <string>
#include <utility>
#include <vector>

#include "loading/history.hpp"

namespace dda {

// Acceleration units a file can be in: m/s², cm/s² (gal) or g (9.80665 m/s²).
enum class AccelerationUnit { MetrePerSecond2, CentimetrePerSecond2, G };
// "m/s2", "m/s^2", "m/s²"; "cm/s2", "cm/s^2", "cm/s²", "gal"; "g". Throws
// dda::Error naming the accepted spellings otherwise.
AccelerationUnit parse_acceleration_unit(const std::string& name);
double metres_per_second2(AccelerationUnit unit);  // the factor to m/s²

class GroundMotion {
 public:
  // Equally spaced accelerations (m/s²), sample i at t = i·dt.
  GroundMotion(double dt, std::vector<double> acceleration, std::string source = "ground motion");
  // Samples at increasing times t (m/s²), resampled linearly to the spacing dt.
  static GroundMotion from_samples(const std::vector<std::pair<double, double>>& samples, double dt,
                                   std::string source);

  // The corrected-accelerogram layout: `%` header lines (one of them
  // "...INTERVALS OF .020 SEC"), then values in free format (8 a line in the
  // file of data/), in `unit` (the USGS/CDMG files are in cm/s²). dt = 0
  // takes the spacing from the header; the header's spacing is required then.
  // A header line "%  1845  INSTRUMENT AND BASELINE CORRECTED DATA" announces
  // the values: a file that holds fewer is truncated and refused.
  static GroundMotion read_accelerogram(const std::string& path,
                                        AccelerationUnit unit = AccelerationUnit::CentimetrePerSecond2, double dt = 0);
  // Two columns, time (s) and acceleration (in `unit`), separated by a comma,
  // semicolon or white space; lines starting with # or % and a first line
  // that is not numbers (a heading) are skipped. Times must increase; uneven
  // spacing is resampled to dt (dt = 0: the smallest spacing in the file).
  static GroundMotion read_csv(const std::string& path, AccelerationUnit unit, double dt = 0);
  // The same from the bytes of a file (`path` names it in messages).
  static GroundMotion parse_accelerogram(std::istream& in, const std::string& path,
                                         AccelerationUnit unit = AccelerationUnit::CentimetrePerSecond2, double dt = 0);
  static GroundMotion parse_csv(std::istream& in, const std::string& path, AccelerationUnit unit, double dt = 0);

  // Memory of a sample, measured over dda.ground_motion (the resampling's
  // and the corrections' copies, and the three tables of {t, value} pairs it
  // returns to Lua): the estimate a resampling is refused on before it
  // allocates (docs/robustness.md).
  static constexpr double kBytesPerSample = 460;

  // The same motion at spacing dt (linear interpolation of the
  // acceleration; the duration is kept, the last sample at or before it).
  GroundMotion resampled(double dt) const;
  // Scaled by a factor (to a target PGA, or to flip the direction).
  GroundMotion scaled(double factor) const;
  // The baseline correction above with a polynomial of degree `order`
  // (0: none, up to 6). Velocity and displacement follow.
  GroundMotion baseline_corrected(int order = 2) const;

  double dt() const { return dt_; }
  std::size_t size() const { return acceleration_.size(); }
  double duration() const { return dt_ * static_cast<double>(size() - 1); }
  const std::string& source() const { return source_; }
  const std::vector<double>& acceleration() const { return acceleration_; }
  const std::vector<double>& velocity() const { return velocity_; }
  const std::vector<double>& displacement() const { return displacement_; }

  // The peak of a series: its value of largest magnitude (sign kept) and when.
  struct Peak {
    double value = 0, time = 0;
  };
  Peak peak_acceleration() const { return peak(acceleration_); }
  Peak peak_velocity() const { return peak(velocity_); }
  Peak peak_displacement() const { return peak(displacement_); }

  // The series as engine histories (piecewise linear through the samples;
  // held at the last value after the record ends).
  History acceleration_history() const { return history(acceleration_, "acceleration"); }
  History velocity_history() const { return history(velocity_, "velocity"); }
  History displacement_history() const { return history(displacement_, "displacement"); }

 private:
  Peak peak(const std::vector<double>& x) const;
  History history(const std::vector<double>& x, const char* what) const;
  void integrate();

  double dt_;
  std::vector<double> acceleration_, velocity_, displacement_;
  std::string source_;
};

}  // namespace dda
