// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// A numbered sequence of frames written during a run: the object the scripting
// layer creates once and calls after every step.
//
//   dda::render::SequenceOptions so;
//   so.folder = "out/frames";
//   so.every_steps = 10;                 // or so.every_time = 1e-4 (s)
//   so.frame.field = dda::render::Field::SigmaYY;
//   dda::render::FrameSequence frames(so);   // creates the folder (dda::Error if it cannot)
//   frames.maybe_capture(world);            // frame 0; also remembers the start (magnify)
//   while (world.time() < t_end) {
//     world.step();
//     frames.maybe_capture(world);          // cheap unless a frame is due
//   }
//   frames.flush();                         // waits for the last PNGs; reports errors
//
// Files are <folder>/<prefix>_<index>.png with the index counting frames from
// 0 (00000, 00001, ...) so ffmpeg's %05d pattern reads them in order; prefix
// defaults to the field's key, e.g. out/frames/sigma_yy_00012.png.
//
// Capturing copies the World into a Scene (cheap) on the caller's thread;
// rendering and PNG encoding happen on a worker thread (FrameWriter), each
// sequence with its own worker and OpenGL context. A FrameSequence is used
// from one thread (the simulation's), between steps.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "frame/renderer.hpp"
#include "output/frame_writer.hpp"
#include "scene/world_scene.hpp"

namespace dda::render {

enum class OnError {
  Stop,      // the error is thrown (dda::Error) from the next maybe_capture/capture/flush
  Continue,  // the error is passed to `warn`, the sequence turns itself off, the run goes on
};

struct SequenceOptions {
  std::filesystem::path folder = "out/frames";
  std::string prefix;     // file name stem; empty → the field key ("sigma_yy"; "frame" for none)
  long every_steps = 0;   // a frame when step_count % every_steps == 0
  double every_time = 0;  // a frame each time simulated time passes a multiple of every_time (s)
                          // (neither set → a frame at every call; both set → dda::Error)
  FrameOptions frame;     // what each frame shows
  // Animation-safe by default: what frame.view and frame.arrow_scale leave
  // open is fixed for the whole sequence, so a block that falls is seen to
  // fall and arrows compare across frames:
  //  - the view from the first frame (the model's bounds then, plus a margin);
  //  - the arrow scale from the first frame in which a block moves (earlier
  //    frames wait for it).
  // Off (fixed = false): each frame fits its own view and arrows.
  // The colour range is never taken from one frame for the others (a range
  // fixed early saturates once the motion grows, and misleads): without
  // frame.range each frame colours by its own range ("range: frame" under
  // the bar, beside the frame's true min and max); frame.range declares a
  // fixed one ("range: fixed", arrow ends where values pass it).
  bool fixed = true;
  // Without frame.range: the range only ever widens over the sequence (the
  // union of every frame's own range so far; "range: grows").
  bool grow_range = false;
  // The window frames are taken in: steps [from_step, to_step] (to_step < 0:
  // no end) and times [from_time, to_time] (s; to_time < 0: no end). With
  // every_steps, frames fall at from_step, from_step + every_steps, ...
  long from_step = 0, to_step = -1;
  double from_time = 0, to_time = -1;
  // A movie made from the frames when the sequence ends (ffmpeg -framerate
  // fps, H.264, yuv420p), when ffmpeg is on the PATH; else a warning says
  // so and the frames stay. Empty: none.
  std::filesystem::path movie;
  int fps = 30;
  int digits = 5;                  // zero-padded width of the index
  std::size_t queue_capacity = 4;  // frames waiting for the worker before the caller waits
  OnError on_error = OnError::Stop;
  std::function<void(const std::string&)> warn;  // for OnError::Continue; default prints to stderr
  bool with_contacts = true;                     // copy contacts into the scene (only drawn if frame.show_contacts)
};

class FrameSequence {
 public:
  // Validates the options and creates the folder. dda::Error naming the
  // folder if it cannot be created or is not a folder.
  explicit FrameSequence(SequenceOptions options);
  ~FrameSequence();  // waits for queued frames (errors then go to stderr)

  // Is a frame due at this step / time (and not yet taken for this step)?
  bool due(long step, double time) const;

  // Captures a frame if one is due; returns whether it did. On the
  // simulation thread this costs a copy of the World's arrays.
  bool maybe_capture(const World& world);
  bool maybe_capture(const Scene& scene);  // uses scene.step and scene.time

  // Captures a frame now, due or not.
  void capture(const World& world);
  void capture(Scene scene);

  // Waits for every queued frame to be written; reports errors per on_error.
  // Frames still waiting for an arrow scale are drawn with their own.
  void flush();

  // flush(), then the movie (once; later calls do nothing). Returns the movie
  // path, or empty when none was made (no movie asked, no frames, no ffmpeg:
  // a warning says which).
  std::filesystem::path finish();

  bool active() const { return active_; }  // false after an error under OnError::Continue
  const std::string& last_error() const { return last_error_; }
  int frame_count() const { return next_index_; }     // frames captured so far
  std::filesystem::path frame_path(int index) const;  // file of frame `index`
  const SequenceOptions& options() const { return options_; }
  // For monitors and the start of the motion (record_initial before the first step).
  WorldSnapshot& snapshot() { return snapshot_; }
  FrameWriter& writer() { return writer_; }

 private:
  void handle(const Error& e);  // per on_error
  void mark_taken(long step, double time);
  void submit(Scene scene, FrameOptions frame, int index);
  void release_pending();
  std::filesystem::path make_movie();

  SequenceOptions options_;
  WorldSnapshot snapshot_;
  FrameWriter writer_;
  int next_index_ = 0;
  std::optional<ValueRange> grown_;
  std::optional<Box> fixed_view_;
  double fixed_arrows_ = 0;
  struct Pending {
    Scene scene;
    FrameOptions frame;
    int index;
  };
  std::vector<Pending> pending_;  // frames waiting for the fixed arrow scale
  bool finished_ = false;
  long last_step_ = -1;
  double next_time_ = 0;
  bool active_ = true;
  std::string last_error_;
};

}  // namespace dda::render
