// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "output/frame_writer.hpp"

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "core/error.hpp"

namespace dda::render {

struct FrameWriter::Impl {
  struct Job {
    std::filesystem::path path;
    std::function<void(std::optional<Renderer>&)> run;
  };

  explicit Impl(std::size_t capacity) : capacity(capacity) {
    worker = std::thread([this] { loop(); });
  }

  ~Impl() {
    {
      std::unique_lock lock(mutex);
      stopping = true;
    }
    not_empty.notify_all();
    worker.join();
    if (!first_error.empty())
      std::fprintf(stderr, "dda render: %zu PNG file(s) could not be written; the first: %s\n", unreported,
                   first_error.c_str());
  }

  void loop() {
    std::optional<Renderer> renderer;  // created, used and destroyed on this thread
    for (;;) {
      Job job;
      {
        std::unique_lock lock(mutex);
        not_empty.wait(lock, [&] { return stopping || !queue.empty(); });
        if (queue.empty()) return;  // stopping, and all done
        job = std::move(queue.front());
        queue.pop_front();
        busy = true;
      }
      not_full.notify_one();
      std::string error;
      try {
        job.run(renderer);
      } catch (const std::exception& e) {
        error = e.what();
        // Name the file unless the message already does.
        if (error.find(job.path.string()) == std::string::npos) error = msg("frame '", job.path.string(), "': ", error);
      } catch (...) {
        error = msg("frame '", job.path.string(), "': unknown error");
      }
      {
        std::unique_lock lock(mutex);
        busy = false;
        if (error.empty())
          ++n_written;
        else {
          ++n_failed;
          if (unreported++ == 0) first_error = error;
        }
      }
      idle.notify_all();
    }
  }

  // Caller side; `lock` held.
  void throw_pending(std::unique_lock<std::mutex>& lock) {
    if (first_error.empty()) return;
    std::string text = first_error;
    if (unreported > 1) text += msg(" (and ", unreported - 1, " more PNG file(s) failed)");
    first_error.clear();
    unreported = 0;
    lock.unlock();
    throw Error(text);
  }

  void submit(Job job) {
    std::unique_lock lock(mutex);
    throw_pending(lock);
    if (queue.size() >= capacity) {
      const auto t0 = std::chrono::steady_clock::now();
      not_full.wait(lock, [&] { return queue.size() < capacity; });
      blocked += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    queue.push_back(std::move(job));
    lock.unlock();
    not_empty.notify_one();
  }

  const std::size_t capacity;
  mutable std::mutex mutex;
  std::condition_variable not_empty, not_full, idle;
  std::deque<Job> queue;
  bool busy = false, stopping = false;
  std::size_t n_written = 0, n_failed = 0, unreported = 0;
  std::string first_error;
  double blocked = 0;
  std::thread worker;  // last: started after everything above exists
};

FrameWriter::FrameWriter(std::size_t queue_capacity) {
  if (queue_capacity < 1) throw Error("frame writer: the queue capacity must be at least 1");
  impl_ = std::make_unique<Impl>(queue_capacity);
}

FrameWriter::~FrameWriter() = default;

void FrameWriter::write_frame(Scene scene, FrameOptions options, std::filesystem::path path) {
  // Cheap checks now, on the caller's thread, so mistakes surface at once.
  options.validate();
  scene.validate();
  auto p = path;
  impl_->submit(
      {std::move(path), [scene = std::move(scene), options = std::move(options), p](std::optional<Renderer>& r) {
         if (!r) r.emplace();
         r->render_to_png(scene, options, p);
       }});
}

void FrameWriter::write_image(Image image, std::filesystem::path path) {
  auto p = path;
  impl_->submit({std::move(path), [image = std::move(image), p](std::optional<Renderer>&) { write_png(image, p); }});
}

void FrameWriter::write_plot(PlotSpec spec, std::filesystem::path path) {
  spec.validate();
  auto p = path;
  impl_->submit({std::move(path), [spec = std::move(spec), p](std::optional<Renderer>&) { write_plot_png(spec, p); }});
}

void FrameWriter::check() {
  std::unique_lock lock(impl_->mutex);
  impl_->throw_pending(lock);
}

void FrameWriter::flush() {
  std::unique_lock lock(impl_->mutex);
  impl_->idle.wait(lock, [&] { return impl_->queue.empty() && !impl_->busy; });
  impl_->throw_pending(lock);
}

std::size_t FrameWriter::pending() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->queue.size() + (impl_->busy ? 1 : 0);
}
std::size_t FrameWriter::written() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->n_written;
}
std::size_t FrameWriter::failed() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->n_failed;
}
double FrameWriter::blocked_seconds() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->blocked;
}

}  // namespace dda::render
