#include "output/frame_sequence.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <system_error>

#include "core/error.hpp"

namespace dda::render {
namespace {

SequenceOptions validated(SequenceOptions o) {
  if (o.every_steps < 0) throw Error(msg("frame sequence: every_steps = ", o.every_steps, " must be >= 0"));
  if (!(o.every_time >= 0) || !std::isfinite(o.every_time))
    throw Error(msg("frame sequence: every_time = ", o.every_time, " s must be >= 0"));
  if (o.every_steps > 0 && o.every_time > 0) throw Error("frame sequence: give every_steps or every_time, not both");
  if (o.digits < 1 || o.digits > 9) throw Error(msg("frame sequence: digits = ", o.digits, " must be 1 .. 9"));
  if (o.queue_capacity < 1) throw Error("frame sequence: the queue capacity must be at least 1");
  if (o.prefix.find('/') != std::string::npos)
    throw Error(
        msg("frame sequence: prefix '", o.prefix, "' must be a file name stem (no '/'); put folders in 'folder'"));
  if (o.prefix.empty()) o.prefix = o.frame.field == Field::None ? "frame" : field_info(o.frame.field).key;
  o.frame.validate();
  if (!o.warn) o.warn = [](const std::string& m) { std::fprintf(stderr, "warning: %s\n", m.c_str()); };

  std::error_code ec;
  std::filesystem::create_directories(o.folder, ec);
  if (ec) throw Error(msg("frame sequence: cannot create the folder '", o.folder.string(), "': ", ec.message()));
  if (!std::filesystem::is_directory(o.folder, ec))
    throw Error(msg("frame sequence: '", o.folder.string(), "' exists and is not a folder"));
  if (::access(o.folder.c_str(), W_OK) != 0)
    throw Error(msg("frame sequence: the folder '", o.folder.string(), "' is not writable: ", std::strerror(errno)));
  return o;
}

}  // namespace

FrameSequence::FrameSequence(SequenceOptions options)
    : options_(validated(std::move(options))), writer_(options_.queue_capacity) {}

FrameSequence::~FrameSequence() = default;

std::filesystem::path FrameSequence::frame_path(int index) const {
  char num[32];
  std::snprintf(num, sizeof num, "%0*d", options_.digits, index);
  return options_.folder / (options_.prefix + "_" + num + ".png");
}

bool FrameSequence::due(long step, double time) const {
  if (!active_ || step == last_step_) return false;
  if (options_.every_steps > 0)
    return last_step_ < 0 || step >= (last_step_ / options_.every_steps + 1) * options_.every_steps;
  if (options_.every_time > 0) return time >= next_time_ - 1e-9 * options_.every_time;
  return true;
}

void FrameSequence::mark_taken(long step, double time) {
  last_step_ = step;
  if (options_.every_time > 0) next_time_ = (std::floor(time / options_.every_time + 1e-9) + 1) * options_.every_time;
}

void FrameSequence::handle(const Error& e) {
  last_error_ = e.what();
  if (options_.on_error == OnError::Stop) throw;
  active_ = false;
  options_.warn(msg(last_error_, " — frame sequence '", options_.prefix, "' in '", options_.folder.string(),
                    "' stopped; the run goes on"));
}

bool FrameSequence::maybe_capture(const Scene& scene) {
  if (!due(scene.step, scene.time)) return false;
  capture(scene);
  return active_;
}

void FrameSequence::capture(Scene scene) {
  if (!active_) return;
  const long step = scene.step;
  const double time = scene.time;
  FrameOptions frame = options_.frame;
  if (options_.grow_range && !frame.range && frame.field != Field::None) {
    const ValueRange r = frame_range(scene, frame.field);
    grown_ = grown_ ? ValueRange{std::min(grown_->min, r.min), std::max(grown_->max, r.max)} : r;
    frame.range = grown_;
  }
  try {
    writer_.write_frame(std::move(scene), std::move(frame), frame_path(next_index_));
  } catch (const Error& e) {
    handle(e);
    return;
  }
  ++next_index_;
  mark_taken(step, time);
}

void FrameSequence::flush() {
  try {
    writer_.flush();
  } catch (const Error& e) {
    if (active_ || options_.on_error == OnError::Stop) handle(e);
  }
}

}  // namespace dda::render
