// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Renderer benchmark: frames per second for a 1280×720 frame of a
// 10,000-block model (a 100 × 100 grid of 1 m squares carrying a synthetic
// stress wave), per stage and through the asynchronous writer.
//
//   build-render/bench/bench_render [frames]      (default 40 frames per row)
//
// Prints, per configuration: ms per frame and frames per second for drawing
// (OSMesa + overlay), PNG encoding, the file write, all of it on the caller's
// thread, and the FrameWriter pipeline (caller cost per frame vs throughput).
#include <unistd.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "raster/text.hpp"
#include "render.hpp"

using namespace dda::render;
using Clock = std::chrono::steady_clock;

namespace {

// A 100 × 100 grid with a plane P-wave travelling in x: σxx = -A·sin(k(x - c t)).
Scene wave_grid(int n, double t, bool contacts) {
  Scene s;
  const double A = 5e6, k = 2 * dda::kPi / 40.0, c = 4000;
  s.vertices.reserve(static_cast<std::size_t>(n) * n * 4);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = i + 0.5, y = j + 0.5, phase = k * (x - c * t * 1e-3);
      const dda::Vec2 q[4] = {{1.0 * i, 1.0 * j}, {i + 1.0, 1.0 * j}, {i + 1.0, j + 1.0}, {1.0 * i, j + 1.0}};
      const double sxx = -A * std::sin(phase), syy = 0.25 * sxx, txy = 0.1 * A * std::cos(phase) * std::sin(y * 0.1);
      const double v = 1e-3 * std::sin(phase);
      s.add_block(q, dda::Vec3(sxx, syy, txy), dda::Vec2(v, 0.2 * v), dda::Vec2(1e-5 * std::cos(phase), 0));
    }
  if (contacts)
    for (std::size_t b = 0; b < s.block_count(); ++b)
      for (int v = 0; v < 4; ++v)
        s.contacts.push_back({static_cast<dda::BlockId>(b), v, static_cast<dda::ContactState>((b + v) % 3)});
  s.time = t;
  s.step = static_cast<long>(t * 1e4);
  return s;
}

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// CPU time of the whole process (every thread, llvmpipe's included): less
// disturbed than wall time on a shared machine.
double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

struct Timer {
  Clock::time_point wall = Clock::now();
  double cpu = cpu_seconds();
};

void row(const char* what, const Timer& t, int frames) {
  const double wall = seconds_since(t.wall), cpu = cpu_seconds() - t.cpu;
  std::printf("  %-44s %8.2f ms/frame %7.1f frames/s   (CPU %7.2f ms/frame)\n", what, 1e3 * wall / frames,
              frames / wall, 1e3 * cpu / frames);
}

}  // namespace

int main(int argc, char** argv) {
  const int frames = argc > 1 ? std::max(1, std::atoi(argv[1])) : 40;
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("dda_bench_render_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);

  const Scene base = wave_grid(100, 0, true);
  std::printf("bench_render: %zu blocks, %zu vertices, %zu contacts; 1280x720; %d frames a row; font %s\n",
              base.block_count(), base.vertices.size(), base.contacts.size(), frames, font_description().c_str());
  const char* lp = std::getenv("LP_NUM_THREADS");
  std::printf("  llvmpipe threads: %s (LP_NUM_THREADS), hardware threads: %u\n", lp ? lp : "default",
              std::thread::hardware_concurrency());

  struct Config {
    const char* name;
    std::function<void(FrameOptions&)> set;
  };
  const Config configs[] = {
      {"sigma_xx, edges", [](FrameOptions&) {}},
      {"sigma_xx, edges + contacts + arrows", [](FrameOptions& o) { o.show_contacts = o.show_velocity = true; }},
      {"von_mises, supersample 2",
       [](FrameOptions& o) {
         o.field = Field::VonMises;
         o.supersample = 2;
       }},
  };

  Renderer renderer;
  renderer.render(base, FrameOptions{});  // context creation and first-use costs, not timed

  for (const Config& c : configs) {
    FrameOptions o;
    o.field = Field::SigmaXX;
    c.set(o);
    std::printf("%s\n", c.name);

    // Scenes are prepared first: the copy out of a World is timed separately below.
    std::vector<Scene> scenes;
    for (int f = 0; f < 4; ++f) scenes.push_back(wave_grid(100, f * 0.1, o.show_contacts));

    Timer t;
    Image last;
    for (int f = 0; f < frames; ++f) last = renderer.render(scenes[f % 4], o).image;
    row("draw (OSMesa + overlay), caller thread", t, frames);

    t = Timer();
    std::size_t bytes = 0;
    for (int f = 0; f < frames; ++f) bytes = encode_png(last).size();
    row("PNG encode", t, frames);

    t = Timer();
    for (int f = 0; f < frames; ++f) write_png(last, dir / "sync.png");
    row("PNG encode + write file", t, frames);
    std::printf("  %-44s %8.1f kB\n", "PNG size", bytes / 1024.0);

    t = Timer();
    for (int f = 0; f < frames; ++f) renderer.render_to_png(scenes[f % 4], o, dir / "sync.png");
    row("draw + encode + write, all on caller thread", t, frames);

    // Through the worker: the caller pays the scene copy and the enqueue
    // (and waits only when the queue is full).
    {
      FrameWriter writer(4);
      double caller = 0;
      Timer t0;
      for (int f = 0; f < frames; ++f) {
        const auto c0 = Clock::now();
        Scene copy = scenes[f % 4];  // stands in for snapshot(world)
        writer.write_frame(std::move(copy), o, dir / ("async_" + std::to_string(f % 8) + ".png"));
        caller += seconds_since(c0);
      }
      writer.flush();
      row("FrameWriter throughput (back to back)", t0, frames);
      std::printf("  %-44s %8.2f ms/frame (waits on a full queue: %.2f ms/frame)\n",
                  "  caller cost per frame, back to back", 1e3 * caller / frames,
                  1e3 * writer.blocked_seconds() / frames);
    }
    {
      // A simulation that captures every 60 ms of work: the caller's cost is the copy.
      FrameWriter writer(4);
      double caller = 0;
      const int n = std::max(1, frames / 4);
      for (int f = 0; f < n; ++f) {
        const auto w0 = Clock::now();
        volatile double sink = 0;
        while (seconds_since(w0) < 0.060) sink = sink + 1;  // "a step"
        const auto c0 = Clock::now();
        Scene copy = scenes[f % 4];
        writer.write_frame(std::move(copy), o, dir / ("paced_" + std::to_string(f % 8) + ".png"));
        caller += seconds_since(c0);
      }
      writer.flush();
      std::printf("  %-44s %8.2f ms/frame\n", "  caller cost per frame, 60 ms steps", 1e3 * caller / n);
    }
  }
  std::filesystem::remove_all(dir);
  return 0;
}
