// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Writes PNGs on a worker thread so rendering and encoding do not stall the
// simulation. The caller hands over a copy of what to draw (a Scene, an Image
// or a PlotSpec) and goes on; the worker renders (its own OpenGL context) and
// encodes. The queue is bounded: when it is full the caller waits, so memory
// stays bounded and no frame is dropped.
//
// Errors on the worker (OSMesa missing, folder not writable, ...) are kept and
// thrown as dda::Error by the caller's next call (write_*, check or flush),
// naming the file; the writer stays usable afterwards. Errors not reported by
// the time the writer is destroyed are printed to stderr.
#include <cstddef>
#include <filesystem>
#include <memory>

#include "frame/renderer.hpp"
#include "plot/plot.hpp"
#include "raster/image.hpp"
#include "scene/scene.hpp"

namespace dda::render {

class FrameWriter {
 public:
  explicit FrameWriter(std::size_t queue_capacity = 4);  // capacity >= 1
  ~FrameWriter();                                        // finishes every queued job, then joins the worker
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  // Queue a job. Each first throws any error the worker has met since the
  // last report (the job is then not queued), and waits while the queue is full.
  void write_frame(Scene scene, FrameOptions options, std::filesystem::path path);
  void write_image(Image image, std::filesystem::path path);
  void write_plot(PlotSpec spec, std::filesystem::path path);

  // Throws the worker's pending error, if any, without waiting.
  void check();
  // Waits until every queued job is done, then throws the pending error, if any.
  void flush();

  std::size_t pending() const;     // queued or in progress
  std::size_t written() const;     // files written so far
  std::size_t failed() const;      // jobs that failed so far
  double blocked_seconds() const;  // time callers spent waiting for queue space

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dda::render
