// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// The machine's memory bandwidth, as STREAM's triad measures it: a = b + s·c
// over arrays of doubles, 24 bytes moved per element (two reads, one write;
// the write-allocate read is not counted, as in STREAM), the best of several
// passes. The engine's large wave problems wait for memory, so their speed is
// read against this figure (docs/performance.md).
//
//   ./build/bench/bench_triad                 # 1 and 2 threads; 3 × 128 MB (memory) and 3 × 1 MB (cache)
//   ./build/bench/bench_triad --threads 1,2,4 --mb 256 --passes 20
//
// Each thread works on its own contiguous share of the arrays (first touched
// by that thread). Prints, per array size and thread count, GB/s: the best
// pass, and the median pass, since a shared machine's other work slows some
// passes.
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

struct Figures {
  double best = 0, median = 0;  // GB/s
};

Figures triad(std::size_t n, int threads, int passes) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  std::vector<double> a(n), b(n), c(n);
  const std::size_t chunk = (n + threads - 1) / threads;
  auto over_shares = [&](auto&& f) {
    tbb::parallel_for(0, threads, [&](int t) {
      const std::size_t begin = std::min(n, t * chunk), end = std::min(n, begin + chunk);
      f(begin, end);
    });
  };
  over_shares([&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) a[i] = 0, b[i] = 1.0 + 1e-9 * i, c[i] = 2.0;
  });
  const double s = 3.0;
  std::vector<double> rates;
  for (int p = 0; p < passes; ++p) {
    const auto t0 = std::chrono::steady_clock::now();
    over_shares([&](std::size_t begin, std::size_t end) {
      double* __restrict ap = a.data();
      const double* __restrict bp = b.data();
      const double* __restrict cp = c.data();
      for (std::size_t i = begin; i < end; ++i) ap[i] = bp[i] + s * cp[i];
    });
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    rates.push_back(24.0 * static_cast<double>(n) / seconds / 1e9);
  }
  // Keep the result alive.
  double check = 0;
  for (std::size_t i = 0; i < n; i += n / 7 + 1) check += a[i];
  if (check == 12345.678) std::printf(" ");
  std::sort(rates.begin(), rates.end());
  return {rates.back(), rates[rates.size() / 2]};
}

std::vector<int> parse_list(const std::string& s) {
  std::vector<int> out;
  std::size_t start = 0;
  while (start < s.size()) {
    const std::size_t end = s.find(',', start);
    out.push_back(std::atoi(s.substr(start, end - start).c_str()));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> threads{1, 2};
  std::vector<int> sizes_mb{128, 1};  // per array: far beyond the caches, and within L2
  int passes = 20;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--threads" && has_value) {
      threads = parse_list(argv[++i]);
    } else if (a == "--mb" && has_value) {
      sizes_mb = parse_list(argv[++i]);
    } else if (a == "--passes" && has_value) {
      passes = std::max(1, std::atoi(argv[++i]));
    } else {
      std::fprintf(stderr, "usage: bench_triad [--threads 1,2] [--mb 128,1] [--passes 20]\n");
      return 2;
    }
  }
  std::printf("%10s %8s %12s %12s\n", "MB/array", "threads", "best GB/s", "median GB/s");
  for (const int mb : sizes_mb)
    for (const int t : threads) {
      const std::size_t n = static_cast<std::size_t>(mb) * 1024 * 1024 / sizeof(double);
      // Cache-sized arrays take many more passes: each lasts microseconds.
      const Figures f = triad(n, t, mb >= 16 ? passes : passes * 50);
      std::printf("%10d %8d %12.1f %12.1f\n", mb, t, f.best, f.median);
    }
}
