// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "reference/plate_bar.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <optional>

#include "core/error.hpp"
#include "core/types.hpp"

namespace dda::reference {

namespace {

const Complex kI(0, 1);

// sin(z)/z, without the cancellation at small z.
Complex sinc(Complex z) { return std::abs(z) < 1e-4 ? 1.0 - z * z / 6.0 : std::sin(z) / z; }

// Chebyshev–Gauss–Lobatto points s_j = cos(jπ/N) on [−1, 1] and the
// differentiation matrix there (Trefethen, Spectral Methods in MATLAB, cheb.m).
void chebyshev(int n, Eigen::VectorXd& s, Eigen::MatrixXd& d) {
  s.resize(n + 1);
  for (int j = 0; j <= n; ++j) s[j] = std::cos(kPi * j / n);
  Eigen::VectorXd c(n + 1);
  for (int j = 0; j <= n; ++j) c[j] = (j == 0 || j == n ? 2.0 : 1.0) * (j % 2 ? -1.0 : 1.0);
  d.setZero(n + 1, n + 1);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      if (i != j) d(i, j) = c[i] / c[j] / (s[i] - s[j]);
  for (int i = 0; i <= n; ++i) d(i, i) = -d.row(i).sum();
}

// Gauss–Legendre nodes and weights on [0, 1].
void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.resize(n), w.resize(n);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
        p0 = p1, p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-15) break;
    }
    x[i] = 0.5 * (1 - z);
    w[i] = 1 / ((1 - z * z) * dp * dp);
  }
}

}  // namespace

PlateModes::PlateModes(const Strip& strip, int collocation_points) : strip_(strip), n_(collocation_points) {
  if (!(strip.density > 0) || !(strip.youngs > 0) || !(strip.height > 0) || !(strip.poisson > -1) ||
      !(strip.poisson < 0.5))
    throw Error("plate reference: density, Young's modulus and height must be positive, -1 < nu < 0.5");
  if (n_ < 6) throw Error("plate reference: at least 6 collocation points");
  const double e = strip.youngs, nu = strip.poisson;
  mu_ = e / (2 * (1 + nu));
  lambda_ = strip.plane == PlaneMode::Stress ? e * nu / (1 - nu * nu) : e * nu / ((1 + nu) * (1 - 2 * nu));
  c_l_ = std::sqrt((lambda_ + 2 * mu_) / strip.density);
  c_t_ = std::sqrt(mu_ / strip.density);
  b_ = strip.height / 2;
}

Complex PlateModes::dispersion(Complex k, Complex omega) const {
  // Scaled by b: kb, pb, qb.
  const Complex kb = k * b_, wl = omega * b_ / c_l_, wt = omega * b_ / c_t_;
  const Complex p = std::sqrt(wl * wl - kb * kb), q = std::sqrt(wt * wt - kb * kb);
  const Complex d = q * q - kb * kb;
  return d * d * std::cos(p) * sinc(q) + 4.0 * kb * kb * p * std::sin(p) * std::cos(q);
}

// The quadratic eigenvalue problem of the collocated half-section, in units
// of b and μ: unknowns u_x and w = −i·u_y at y_j ∈ [0, 1]; rows: the Navier
// equations inside, σxy = σyy = 0 at y = 1, symmetry (u_x' = 0, u_y = 0)
// at y = 0. (k²·M2 + k·M1 + M0)·U = 0, linearised to A·z = k·B·z.
std::vector<Complex> PlateModes::eigenvalue_estimates(double omega) const {
  // Enough points for the cross-section's shortest wave at this frequency
  // (about ωb/c_T radians over the half-height).
  const int n = std::max(n_, static_cast<int>(std::ceil(1.5 * omega * b_ / c_t_)) + 12), m = n + 1, size = 2 * m;
  Eigen::VectorXd s;
  Eigen::MatrixXd d;
  chebyshev(n, s, d);
  d *= 2.0;  // y = (s + 1)/2 on [0, 1]: point 0 is the surface y = 1, point n the mid-plane y = 0
  const Eigen::MatrixXd d2 = d * d;
  const double kappa = lambda_ / mu_, w2 = std::pow(omega * b_ / c_t_, 2);
  Eigen::MatrixXd m0 = Eigen::MatrixXd::Zero(size, size), m1 = m0, m2 = m0;
  const int ux = 0, w = m;  // column offsets
  for (int j = 0; j < m; ++j) {
    const int r1 = j, r2 = m + j;
    if (j == 0) {  // the surface: σxy/μ = u_x' − k·w, σyy/μ = κ·k·u_x + (κ + 2)·w'
      m0.block(r1, ux, 1, m) = d.row(0);
      m1(r1, w + 0) = -1;
      m1(r2, ux + 0) = kappa;
      m0.block(r2, w, 1, m) = (kappa + 2) * d.row(0);
    } else if (j == n) {  // the mid-plane
      m0.block(r1, ux, 1, m) = d.row(n);
      m0(r2, w + n) = 1;
    } else {
      m0(r1, ux + j) += w2;
      m0.block(r1, ux, 1, m) += d2.row(j);
      m2(r1, ux + j) = -(kappa + 2);
      m1.block(r1, w, 1, m) = -(kappa + 1) * d.row(j);
      m0(r2, w + j) += w2;
      m0.block(r2, w, 1, m) += (kappa + 2) * d2.row(j);
      m2(r2, w + j) = -1;
      m1.block(r2, ux, 1, m) = (kappa + 1) * d.row(j);
    }
  }
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * size, 2 * size), bm = a;
  a.block(0, size, size, size).setIdentity();
  a.block(size, 0, size, size) = -m0;
  a.block(size, size, size, size) = -m1;
  bm.block(0, 0, size, size).setIdentity();
  bm.block(size, size, size, size) = m2;
  Eigen::GeneralizedEigenSolver<Eigen::MatrixXd> qz(a, bm, false);
  std::vector<Complex> k;
  for (int i = 0; i < 2 * size; ++i) {
    const Complex alpha = qz.alphas()[i];
    const double beta = qz.betas()[i];
    if (std::abs(beta) > 1e-10 * std::abs(alpha) && std::abs(beta) > 0) k.push_back(alpha / beta / b_);
  }
  return k;
}

std::optional<Complex> PlateModes::polish(Complex k, Complex omega) const {
  for (int it = 0; it < 60; ++it) {
    const Complex h = 1e-7 * (1.0 + std::abs(k) * b_) / b_;
    const Complex f = dispersion(k, omega);
    const Complex df = (dispersion(k + h, omega) - dispersion(k - h, omega)) / (2.0 * h);
    if (df == 0.0 || !std::isfinite(std::abs(df))) return std::nullopt;
    const Complex step = f / df;
    k -= step;
    if (!std::isfinite(std::abs(k))) return std::nullopt;
    if (std::abs(step) * b_ < 1e-12 * (1 + std::abs(k) * b_)) return k;
  }
  return std::nullopt;
}

PlateMode PlateModes::mode(Complex k, Complex omega) const {
  PlateMode md;
  md.k = k;
  md.p = std::sqrt(omega * omega / (c_l_ * c_l_) - k * k);
  md.q = std::sqrt(omega * omega / (c_t_ * c_t_) - k * k);
  const Complex pb = md.p * b_, qb = md.q * b_;
  // Two ways to meet the surface conditions (σyy = 0 and σxy = 0 at y = b);
  // at a root they agree up to a factor: the larger is kept.
  const Complex a1 = 2.0 * kI * k * std::cos(qb), b1 = -(md.q * md.q - k * k) * std::cos(pb);
  const Complex a2 = (k * k - md.q * md.q) * sinc(qb) * b_, b2 = 2.0 * kI * k * md.p * std::sin(pb);
  if (std::abs(a1) + std::abs(b1) >= std::abs(a2) + std::abs(b2))
    md.a = a1, md.b = b1;
  else
    md.a = a2, md.b = b2;
  return md;
}

ModeFields PlateModes::fields(const PlateMode& m, Complex /*omega*/, double y) const {
  const Complex k = m.k, p = m.p, q = m.q, a = m.a, b = m.b;
  const Complex cp = std::cos(p * y), cq = std::cos(q * y);
  const Complex psp = p * std::sin(p * y), sq = sinc(q * y) * y;  // p·sin(py), sin(qy)/q
  ModeFields f;
  f.ux = kI * k * a * cp + b * cq;
  f.uy = -a * psp - kI * k * b * sq;
  f.sxx = mu_ * (-(k * k + q * q - 2.0 * p * p) * a * cp + 2.0 * kI * k * b * cq);
  f.syy = mu_ * (-(q * q - k * k) * a * cp - 2.0 * kI * k * b * cq);
  f.sxy = mu_ * (-2.0 * kI * k * a * psp + (k * k - q * q) * b * sq);
  return f;
}

std::vector<Complex> PlateModes::right_going_wavenumbers(Complex omega, int count) const {
  const double omega_real = std::max(omega.real(), 1e-3 * c_t_ / b_);
  std::vector<Complex> roots;
  for (const Complex estimate : eigenvalue_estimates(omega_real)) {
    const std::optional<Complex> k = polish(estimate, omega);
    if (k && k->imag() > 0 && !contains(roots, *k)) roots.push_back(*k);
  }
  std::sort(roots.begin(), roots.end(), [](Complex x, Complex y) { return x.imag() < y.imag(); });
  if (static_cast<int>(roots.size()) > count) roots.resize(count);
  return roots;
}

bool PlateModes::contains(const std::vector<Complex>& roots, Complex k) const {
  for (const Complex r : roots)
    if (std::abs(r - k) * b_ < 1e-7 * (1 + std::abs(k) * b_)) return true;
  return false;
}

std::vector<PlateMode> PlateModes::right_going(Complex omega, int count) const {
  std::vector<PlateMode> modes;
  for (const Complex k : right_going_wavenumbers(omega, count)) modes.push_back(mode(k, omega));
  return modes;
}

std::optional<std::vector<Complex>> PlateModes::follow(const std::vector<Complex>& predicted, Complex omega) const {
  std::vector<Complex> roots;
  for (const Complex guess : predicted) {
    const std::optional<Complex> k = polish(guess, omega);
    if (!k || k->imag() <= 0 || contains(roots, *k) || std::abs(*k - guess) * b_ > 0.05 * (1 + std::abs(guess) * b_))
      return std::nullopt;
    roots.push_back(*k);
  }
  return roots;
}

double load_at(const std::vector<std::pair<double, double>>& load, double t) {
  if (t < load.front().first || t > load.back().first) return 0;
  for (std::size_t j = 0; j + 1 < load.size(); ++j)
    if (t <= load[j + 1].first) {
      const auto [t0, v0] = load[j];
      const auto [t1, v1] = load[j + 1];
      return t1 > t0 ? v0 + (v1 - v0) * (t - t0) / (t1 - t0) : v1;
    }
  return 0;
}

Complex piecewise_linear_transform(const std::vector<std::pair<double, double>>& load, Complex omega) {
  // ∫ (v0 + s·(t − t0))·e^{iωt} dt over each segment, exactly.
  const Complex iw = kI * omega;
  Complex sum = 0;
  for (std::size_t j = 0; j + 1 < load.size(); ++j) {
    const auto [t0, v0] = load[j];
    const auto [t1, v1] = load[j + 1];
    const double h = t1 - t0;
    if (!(h > 0)) continue;
    const Complex z = iw * h;
    Complex i0, i1;  // ∫₀ʰ e^{iωτ}dτ and ∫₀ʰ τ·e^{iωτ}dτ
    if (std::abs(z) < 1e-3) {
      i0 = h * (1.0 + z / 2.0 + z * z / 6.0 + z * z * z / 24.0);
      i1 = h * h * (0.5 + z / 3.0 + z * z / 8.0 + z * z * z / 30.0);
    } else {
      const Complex e = std::exp(z);
      i0 = (e - 1.0) / iw;
      i1 = (h * e - i0) / iw;
    }
    sum += std::exp(iw * t0) * (v0 * i0 + (v1 - v0) / h * i1);
  }
  return sum;
}

std::vector<double> plate_bar_stress(const Strip& strip, const std::vector<std::pair<double, double>>& load, double x,
                                     double y, const std::vector<double>& times, const PlateBarOptions& o) {
  if (load.size() < 2) throw Error("plate reference: the load needs at least two points");
  if (!(o.max_frequency > 0) || !(o.frequency_step > 0) || o.max_frequency < 10 * o.frequency_step)
    throw Error("plate reference: max_frequency must be positive and at least 10 frequency steps");
  if (o.modes < 1) throw Error("plate reference: keep at least one mode");
  const PlateModes modes(strip, o.collocation_points);
  const double b = modes.half_height();
  if (std::abs(y) > b) throw Error("plate reference: the receiver is outside the strip");
  // The exponential window: what would wrap round from one period 1/Δf later
  // is damped by e^{−ε/Δf} = 1e-8.
  const double eps = std::log(1e8) * o.frequency_step;
  std::vector<double> gx, gw;
  gauss_legendre(64, gx, gw);
  const int count = static_cast<int>(std::floor(o.max_frequency / o.frequency_step));
  std::vector<Complex> sum(times.size(), 0.0);
  // The bar's long-wave speed: the 1-D answer −p(t − x/c0), exact in the
  // limit of long waves (and at every frequency with ν = 0), is added as
  // it is; the synthesis carries the rest, G − G_1D with G_1D = −e^{iωx/c0}.
  const double plane_modulus =
      strip.plane == PlaneMode::Stress ? strip.youngs : strip.youngs / (1 - strip.poisson * strip.poisson);
  const double c0 = std::sqrt(plane_modulus / strip.density);
  // The modes that reach the receiver: every one whose decay over x leaves
  // more than e^{−40} (all that propagate, and evanescent ones near their
  // cut-off); a free end's fit takes at least o.modes.
  auto reaches = [x](Complex k) { return k.imag() * std::max(x, 1e-9) < 40; };
  // The modes are followed from frequency to frequency by Newton's method
  // from their extrapolated wavenumbers, found afresh (QZ) every 50 steps
  // and whenever one is lost; four more than are used are followed, so
  // that one coming up from deeper decay is among them.
  std::vector<Complex> roots, before;
  for (int j = 0; j <= count; ++j) {
    const double f = j * o.frequency_step;
    const Complex omega(2 * kPi * f, eps);
    std::optional<std::vector<Complex>> next;
    if (j % 50 != 0 && !roots.empty()) {
      std::vector<Complex> guess = roots;
      if (before.size() == roots.size())
        for (std::size_t n = 0; n < roots.size(); ++n) guess[n] = 2.0 * roots[n] - before[n];
      next = modes.follow(guess, omega);
    }
    before = next ? roots : std::vector<Complex>{};
    if (next) {
      roots = *next;
    } else {
      roots = modes.right_going_wavenumbers(omega, 1000);
      int used = 0;
      for (const Complex k : roots) used += reaches(k) ? 1 : 0;
      if (o.end == EndCondition::Free) used = std::max(used, o.modes);
      if (static_cast<int>(roots.size()) > used + 4) roots.resize(used + 4);
    }
    std::vector<Complex> sorted = roots;
    std::sort(sorted.begin(), sorted.end(), [](Complex x, Complex y) { return x.imag() < y.imag(); });
    std::vector<PlateMode> ms;
    for (const Complex k : sorted)
      if (reaches(k) || (o.end == EndCondition::Free && static_cast<int>(ms.size()) < o.modes))
        ms.push_back(modes.mode(k, omega));
    // The modes' amplitudes per unit pressure, then G at the receiver.
    std::vector<Complex> amp(ms.size(), 0.0);
    if (o.end == EndCondition::Rollers) {
      for (std::size_t n = 0; n < ms.size(); ++n) {
        Complex ux = 0, norm = 0;
        for (std::size_t g = 0; g < gx.size(); ++g) {
          const ModeFields fl = modes.fields(ms[n], omega, b * gx[g]);
          ux += gw[g] * fl.ux;
          norm += gw[g] * (fl.sxx * fl.ux - fl.sxy * fl.uy);
        }
        amp[n] = -ux / norm;  // σxx = −p at the end; the integrals over ±b are twice those over [0, b]
      }
    } else {
      // Least squares of the end tractions (σxx + p, σxy) at the Gauss
      // points of [0, b], weighted by √w: the L² misfit over the end.
      const int rows = 2 * static_cast<int>(gx.size()), cols = static_cast<int>(ms.size());
      Eigen::MatrixXcd a(rows, cols);
      Eigen::VectorXcd rhs(rows);
      Eigen::VectorXd scale(cols);
      for (int n = 0; n < cols; ++n) {
        for (std::size_t g = 0; g < gx.size(); ++g) {
          const ModeFields fl = modes.fields(ms[n], omega, b * gx[g]);
          const double sw = std::sqrt(gw[g]);
          a(2 * g, n) = sw * fl.sxx;
          a(2 * g + 1, n) = sw * fl.sxy;
          rhs[2 * g] = -sw;
          rhs[2 * g + 1] = 0;
        }
        scale[n] = a.col(n).norm();
        a.col(n) /= scale[n];
      }
      const Eigen::VectorXcd c = a.colPivHouseholderQr().solve(rhs);
      for (int n = 0; n < cols; ++n) amp[n] = c[n] / scale[n];
    }
    Complex g = std::exp(kI * omega * (x / c0));  // less G_1D
    for (std::size_t n = 0; n < ms.size(); ++n)
      g += amp[n] * modes.fields(ms[n], omega, y).sxx * std::exp(kI * ms[n].k * x);
    // Trapezoid in ω, a cosine taper over the last fifth of the band.
    double weight = (j == 0 || j == count) ? 0.5 : 1.0;
    const double taper_start = 0.8 * o.max_frequency;
    if (f > taper_start) weight *= 0.5 * (1 + std::cos(kPi * (f - taper_start) / (o.max_frequency - taper_start)));
    const Complex c = weight * piecewise_linear_transform(load, omega) * g;
    for (std::size_t i = 0; i < times.size(); ++i) sum[i] += c * std::exp(-kI * omega * times[i]);
  }
  std::vector<double> sigma(times.size());
  const double dw = 2 * kPi * o.frequency_step;
  for (std::size_t i = 0; i < times.size(); ++i) sigma[i] = sum[i].real() * dw / kPi - load_at(load, times[i] - x / c0);
  return sigma;
}

}  // namespace dda::reference
