// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "output/frame_sequence.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <system_error>
#include <vector>

#include "core/error.hpp"

extern char** environ;

namespace dda::render {
namespace {

SequenceOptions validated(SequenceOptions o) {
  if (o.every_steps < 0) throw Error(msg("frame sequence: every_steps = ", o.every_steps, " must be >= 0"));
  if (!(o.every_time >= 0) || !std::isfinite(o.every_time))
    throw Error(msg("frame sequence: every_time = ", o.every_time, " s must be >= 0"));
  if (o.every_steps > 0 && o.every_time > 0) throw Error("frame sequence: give every_steps or every_time, not both");
  if (o.digits < 1 || o.digits > 9) throw Error(msg("frame sequence: digits = ", o.digits, " must be 1 .. 9"));
  if (o.from_step < 0) throw Error(msg("frame sequence: the first step ", o.from_step, " must be >= 0"));
  if (o.to_step >= 0 && o.to_step < o.from_step)
    throw Error(msg("frame sequence: the last step ", o.to_step, " comes before the first ", o.from_step));
  if (!std::isfinite(o.from_time) || !std::isfinite(o.to_time) || o.from_time < 0 ||
      (o.to_time >= 0 && o.to_time < o.from_time))
    throw Error(msg("frame sequence: the time window [", o.from_time, ", ", o.to_time, "] s is not a window"));
  if (o.fps < 1 || o.fps > 240) throw Error(msg("frame sequence: fps = ", o.fps, " must be 1 .. 240"));
  if (o.queue_capacity < 1) throw Error("frame sequence: the queue capacity must be at least 1");
  if (o.prefix.find('/') != std::string::npos)
    throw Error(
        msg("frame sequence: prefix '", o.prefix, "' must be a file name stem (no '/'); put folders in 'folder'"));
  if (o.prefix.empty()) o.prefix = o.frame.field == Field::None ? "frame" : field_info(o.frame.field).key;
  o.frame.validate();
  if (!o.warn) o.warn = [](const std::string& m) { std::fprintf(stderr, "warning: %s\n", m.c_str()); };
  return o;
}

// Throws dda::Error when frames cannot be written into the folder.
void prepare_folder(const SequenceOptions& o) {
  std::error_code ec;
  std::filesystem::create_directories(o.folder, ec);
  if (ec) throw Error(msg("frame sequence: cannot create the folder '", o.folder.string(), "': ", ec.message()));
  if (!std::filesystem::is_directory(o.folder, ec))
    throw Error(msg("frame sequence: '", o.folder.string(), "' exists and is not a folder"));
  if (::access(o.folder.c_str(), W_OK) != 0)
    throw Error(msg("frame sequence: the folder '", o.folder.string(), "' is not writable: ", std::strerror(errno)));
}

}  // namespace

FrameSequence::FrameSequence(SequenceOptions options)
    : options_(validated(std::move(options))), writer_(options_.queue_capacity) {
  // An unusable folder is a failing frame like any other: under
  // OnError::Continue (--frames) a warning, and the run goes on.
  try {
    prepare_folder(options_);
  } catch (const Error& e) {
    handle(e);
  }
}

FrameSequence::~FrameSequence() {
  try {
    finish();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "warning: frame sequence in '%s': %s\n", options_.folder.c_str(), e.what());
  }
}

std::filesystem::path FrameSequence::frame_path(int index) const {
  char num[32];
  std::snprintf(num, sizeof num, "%0*d", options_.digits, index);
  return options_.folder / (options_.prefix + "_" + num + ".png");
}

bool FrameSequence::due(long step, double time) const {
  if (!active_ || step == last_step_) return false;
  const SequenceOptions& o = options_;
  if (step < o.from_step || (o.to_step >= 0 && step > o.to_step)) return false;
  const double slack = 1e-9 * std::max({o.every_time, o.from_time, o.to_time, 0.0});
  if (time < o.from_time - slack || (o.to_time >= 0 && time > o.to_time + slack)) return false;
  if (o.every_steps > 0)
    return last_step_ < o.from_step ||
           step >= o.from_step + ((last_step_ - o.from_step) / o.every_steps + 1) * o.every_steps;
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
  bool wait = false;  // for the fixed arrow scale
  if (options_.grow_range && !frame.range && frame.field != Field::None) {
    const ValueRange r = frame_range(scene, frame.field);
    grown_ = grown_ ? ValueRange{std::min(grown_->min, r.min), std::max(grown_->max, r.max)} : r;
    frame.range = grown_;
    frame.range_grows = true;
  }
  if (options_.fixed) {
    if (!frame.view) {
      if (!fixed_view_) fixed_view_ = frame_view(scene, frame.magnify);
      frame.view = fixed_view_;
    }
    if (frame.show_velocity && frame.arrow_scale == 0) {
      if (fixed_arrows_ == 0) fixed_arrows_ = auto_arrow_scale(scene, *frame.view);
      frame.arrow_scale = fixed_arrows_;
      wait = wait || fixed_arrows_ == 0;
    }
  }
  const int index = next_index_++;
  mark_taken(step, time);
  if (wait && pending_.size() < 64) {
    pending_.push_back({std::move(scene), std::move(frame), index});
    return;
  }
  release_pending();
  submit(std::move(scene), std::move(frame), index);
}

void FrameSequence::submit(Scene scene, FrameOptions frame, int index) {
  if (!active_) return;
  try {
    writer_.write_frame(std::move(scene), std::move(frame), frame_path(index));
  } catch (const Error& e) {
    handle(e);
  }
}

// Frames that waited: with the arrow scale now fixed (or, at the end of a
// sequence that never got one, with their own).
void FrameSequence::release_pending() {
  std::vector<Pending> pending;
  pending.swap(pending_);
  for (Pending& p : pending) {
    if (p.frame.show_velocity && p.frame.arrow_scale == 0) p.frame.arrow_scale = fixed_arrows_;
    submit(std::move(p.scene), std::move(p.frame), p.index);
  }
}

void FrameSequence::flush() {
  release_pending();
  try {
    writer_.flush();
  } catch (const Error& e) {
    if (active_ || options_.on_error == OnError::Stop) handle(e);
  }
}

std::filesystem::path FrameSequence::finish() {
  if (finished_) return {};
  finished_ = true;
  flush();
  return make_movie();
}

namespace {

// The program's path on $PATH, or empty.
std::string on_path(const char* program) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    std::size_t end = dirs.find(':', start);
    if (end == std::string::npos) end = dirs.size();
    const std::string dir = end > start ? dirs.substr(start, end - start) : ".";
    const std::string candidate = dir + "/" + program;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
    start = end + 1;
  }
  return {};
}

}  // namespace

std::filesystem::path FrameSequence::make_movie() {
  const SequenceOptions& o = options_;
  if (o.movie.empty() || next_index_ == 0) return {};
  const std::string ffmpeg = on_path("ffmpeg");
  if (ffmpeg.empty()) {
    o.warn(msg("ffmpeg is not on the PATH: no movie '", o.movie.string(), "'; the frames are in '", o.folder.string(),
               "' (WITH_FFMPEG=1 scripts/setup.sh installs ffmpeg)"));
    return {};
  }
  std::error_code ec;
  if (o.movie.has_parent_path()) std::filesystem::create_directories(o.movie.parent_path(), ec);
  // Into a side file first: a failed encode never leaves half a movie.
  const std::filesystem::path part = o.movie.parent_path() / (".part-" + o.movie.filename().string());
  const std::filesystem::path log = o.movie.string() + ".log";
  char pattern[64];
  std::snprintf(pattern, sizeof pattern, "_%%0%dd.png", o.digits);
  const std::string ext = o.movie.extension().string();
  std::vector<std::string> args = {ffmpeg,
                                   "-y",
                                   "-nostdin",
                                   "-loglevel",
                                   "error",
                                   "-framerate",
                                   std::to_string(o.fps),
                                   "-start_number",
                                   "0",
                                   "-i",
                                   (o.folder / (o.prefix + pattern)).string()};
  if (ext == ".mp4" || ext == ".mkv" || ext == ".mov" || ext == ".m4v")
    args.insert(args.end(), {"-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-pix_fmt", "yuv420p"});
  args.push_back(part.string());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, ffmpeg.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  int status = 0;
  if (rc == 0) {
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
  }
  if (rc != 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::filesystem::remove(part, ec);
    o.warn(msg("ffmpeg could not make the movie '", o.movie.string(), "' (", rc ? std::strerror(rc) : "it failed",
               "; see '", log.string(), "'); the frames are in '", o.folder.string(), "'"));
    return {};
  }
  std::filesystem::rename(part, o.movie, ec);
  if (ec) {
    o.warn(msg("cannot write the movie '", o.movie.string(), "': ", ec.message()));
    return {};
  }
  std::filesystem::remove(log, ec);
  return o.movie;
}

}  // namespace dda::render
