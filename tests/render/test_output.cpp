// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Writing files: unwritable folders, no OpenGL context, the asynchronous
// writer's error reporting, and frame sequences (numbering, every N steps /
// every Δt, error policy).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "core/error.hpp"
#include "frame/renderer.hpp"
#include "output/frame_sequence.hpp"
#include "output/frame_writer.hpp"

namespace fs = std::filesystem;
using dda::Vec2;
using dda::Vec3;
using namespace dda::render;

namespace {

fs::path temp_dir(const std::string& name) {
  fs::path p = fs::temp_directory_path() / ("dda_render_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

// A path that cannot be written even by root: its "folder" is a regular file.
fs::path unwritable(const fs::path& dir) {
  const fs::path file = dir / "not_a_folder";
  std::ofstream(file) << "x";
  return file / "frames";
}

Scene small_scene(long step = 0, double time = 0) {
  Scene s;
  for (int i = 0; i < 3; ++i) {
    const std::vector<Vec2> q{{1.0 * i, 0}, {i + 1.0, 0}, {i + 1.0, 1}, {1.0 * i, 1}};
    s.add_block(q, Vec3(i * 1e6, -i * 1e6, 0));
  }
  s.step = step;
  s.time = time;
  return s;
}

FrameOptions small_frame() {
  FrameOptions o;
  o.width = 160, o.height = 120;
  return o;
}

// "f" + 3 → "f3.png" (built without operator+ on temporaries, which trips a
// GCC 12 -Wrestrict false positive).
std::string numbered(const char* stem, int i) {
  std::string out = stem;
  out += std::to_string(i);
  out += ".png";
  return out;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Makes OSMesa context creation fail while alive (test hook).
struct NoOsmesa {
  NoOsmesa() { set_osmesa_disabled_for_testing(true); }
  ~NoOsmesa() { set_osmesa_disabled_for_testing(false); }
};

}  // namespace

TEST(Output, RenderToUnwritableFolderIsAnErrorNamingThePath) {
  const fs::path dir = temp_dir("unwritable");
  const fs::path target = unwritable(dir) / "f.png";
  Renderer r;
  try {
    r.render_to_png(small_scene(), small_frame(), target);
    FAIL() << "no error";
  } catch (const dda::Error& e) {
    EXPECT_TRUE(contains(e.what(), target.string())) << e.what();
  }
  // The renderer carries on.
  EXPECT_NO_THROW(r.render_to_png(small_scene(), small_frame(), dir / "ok.png"));
  EXPECT_TRUE(fs::exists(dir / "ok.png"));
  EXPECT_FALSE(fs::exists(dir / "ok.png.part"));
  fs::remove_all(dir);
}

TEST(Output, NoOpenGLContextIsAClearErrorAndTheCallerCarriesOn) {
  Renderer r;
  r.render(small_scene(), small_frame());  // a context exists already
  {
    NoOsmesa off;
    try {
      r.render(small_scene(), small_frame());
      FAIL() << "no error";
    } catch (const dda::Error& e) {
      EXPECT_TRUE(contains(e.what(), "OpenGL context")) << e.what();
      EXPECT_TRUE(contains(e.what(), "OSMesa")) << e.what();
    }
    EXPECT_THROW(Renderer().render(small_scene(), small_frame()), dda::Error);
  }
  // OSMesa back: the same renderer works again.
  const Frame f = r.render(small_scene(), small_frame());
  EXPECT_EQ(f.image.width(), 160);
}

TEST(Output, EnvironmentVariableDisablesOSMesa) {
  Renderer r;
  ::setenv("DDA_RENDER_DISABLE_OSMESA", "1", 1);
  try {
    r.render(small_scene(), small_frame());
    ::unsetenv("DDA_RENDER_DISABLE_OSMESA");
    FAIL() << "no error";
  } catch (const dda::Error& e) {
    ::unsetenv("DDA_RENDER_DISABLE_OSMESA");
    EXPECT_TRUE(contains(e.what(), "DDA_RENDER_DISABLE_OSMESA")) << e.what();
  }
  EXPECT_NO_THROW(r.render(small_scene(), small_frame()));
}

TEST(Output, WorkerErrorsAreReportedAtTheNextCallNamingTheFile) {
  const fs::path dir = temp_dir("writer");
  const fs::path bad = unwritable(dir) / "a.png";
  FrameWriter w(2);
  w.write_image(Image(8, 8), bad);
  try {
    w.flush();
    FAIL() << "no error";
  } catch (const dda::Error& e) {
    EXPECT_TRUE(contains(e.what(), bad.string())) << e.what();
  }
  EXPECT_EQ(w.failed(), 1u);
  // Reported once; the writer stays usable.
  EXPECT_NO_THROW(w.flush());
  w.write_image(Image(8, 8), dir / "b.png");
  w.write_frame(small_scene(), small_frame(), dir / "c.png");
  EXPECT_NO_THROW(w.flush());
  EXPECT_EQ(w.written(), 2u);
  EXPECT_TRUE(fs::exists(dir / "b.png"));
  EXPECT_TRUE(fs::exists(dir / "c.png"));

  // An error met by the worker surfaces at the next write_* call, not only at flush.
  w.write_image(Image(8, 8), bad);
  while (w.pending() > 0) std::this_thread::yield();
  EXPECT_THROW(w.write_image(Image(8, 8), dir / "d.png"), dda::Error);
  EXPECT_FALSE(fs::exists(dir / "d.png")) << "a job refused with an error is not queued";
  fs::remove_all(dir);
}

TEST(Output, WorkerWithoutOpenGLReportsTheErrorThenRecovers) {
  const fs::path dir = temp_dir("writer_gl");
  FrameWriter w;
  {
    NoOsmesa off;
    w.write_frame(small_scene(), small_frame(), dir / "x.png");
    try {
      w.flush();
      FAIL() << "no error";
    } catch (const dda::Error& e) {
      EXPECT_TRUE(contains(e.what(), "OpenGL context")) << e.what();
      EXPECT_TRUE(contains(e.what(), (dir / "x.png").string())) << e.what();
    }
  }
  w.write_frame(small_scene(), small_frame(), dir / "y.png");
  EXPECT_NO_THROW(w.flush());
  EXPECT_TRUE(fs::exists(dir / "y.png"));
  fs::remove_all(dir);
}

TEST(Output, ManyFramesThroughASmallQueueAllArrive) {
  const fs::path dir = temp_dir("queue");
  {
    FrameWriter w(1);
    for (int i = 0; i < 12; ++i) w.write_frame(small_scene(i, i * 0.1), small_frame(), dir / numbered("f", i));
    w.flush();
    EXPECT_EQ(w.written(), 12u);
  }
  for (int i = 0; i < 12; ++i) EXPECT_TRUE(fs::exists(dir / numbered("f", i))) << i;
  // Destruction without flush still writes everything queued.
  {
    FrameWriter w(2);
    for (int i = 0; i < 5; ++i) w.write_frame(small_scene(), small_frame(), dir / numbered("g", i));
  }
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(fs::exists(dir / numbered("g", i))) << i;
  fs::remove_all(dir);
}

TEST(Sequence, EveryNStepsWritesNumberedFiles) {
  const fs::path dir = temp_dir("seq_steps");
  SequenceOptions so;
  so.folder = dir / "frames";  // created by the sequence
  so.every_steps = 10;
  so.frame = small_frame();
  FrameSequence seq(so);
  int taken = 0;
  for (long step = 0; step <= 35; ++step) taken += seq.maybe_capture(small_scene(step, step * 1e-3));
  EXPECT_FALSE(seq.maybe_capture(small_scene(30, 0.03))) << "one frame per step";
  seq.flush();
  EXPECT_EQ(taken, 4);  // steps 0, 10, 20, 30
  EXPECT_EQ(seq.frame_count(), 4);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(seq.frame_path(i), dir / "frames" / ("sigma_yy_0000" + std::to_string(i) + ".png"));
    EXPECT_TRUE(fs::exists(seq.frame_path(i))) << seq.frame_path(i);
  }
  EXPECT_FALSE(fs::exists(seq.frame_path(4)));
  fs::remove_all(dir);
}

TEST(Sequence, EveryDeltaTAndSkippedSteps) {
  const fs::path dir = temp_dir("seq_time");
  SequenceOptions so;
  so.folder = dir;
  so.prefix = "wave";
  so.every_time = 0.01;
  so.frame = small_frame();
  FrameSequence seq(so);
  // Steps of 3 ms: frames at t = 0, the first t >= 0.01, >= 0.02, >= 0.03.
  std::vector<long> steps;
  for (long step = 0; step <= 11; ++step)
    if (seq.maybe_capture(small_scene(step, step * 0.003))) steps.push_back(step);
  EXPECT_EQ(steps, (std::vector<long>{0, 4, 7, 10}));
  // every_steps with irregular calls: a frame as soon as a multiple is passed.
  SequenceOptions so2 = so;
  so2.every_time = 0;
  so2.every_steps = 5;
  so2.prefix = "n";
  FrameSequence seq2(so2);
  steps.clear();
  for (long step : {0, 3, 6, 7, 9, 12, 16})
    if (seq2.maybe_capture(small_scene(step, 0))) steps.push_back(step);
  EXPECT_EQ(steps, (std::vector<long>{0, 6, 12, 16}));
  seq.flush();
  seq2.flush();
  EXPECT_TRUE(fs::exists(dir / "wave_00003.png"));
  fs::remove_all(dir);
}

TEST(Sequence, GrowingRangeKeepsColoursSteady) {
  const fs::path dir = temp_dir("seq_grow");
  SequenceOptions so;
  so.folder = dir;
  so.frame = small_frame();
  so.frame.field = Field::SigmaXX;
  so.grow_range = true;
  FrameSequence seq(so);
  // Frame 0: |σxx| up to 2 MPa; frame 1: up to 1 MPa. Frame 1 keeps ±2 MPa.
  seq.capture(small_scene(0, 0));
  Scene quieter = small_scene(1, 0);
  for (Vec3& s : quieter.stress) s /= 2;
  seq.capture(quieter);
  seq.flush();
  EXPECT_DOUBLE_EQ(frame_range(small_scene(), Field::SigmaXX).max, 2e6);
  EXPECT_DOUBLE_EQ(frame_range(quieter, Field::SigmaXX).max, 1e6);
  // The block with σxx = 1 MPa in frame 1 is drawn with the colour of 1 MPa on a ±2 MPa bar.
  Renderer r;
  FrameOptions o = small_frame();
  o.field = Field::SigmaXX;
  o.range = ValueRange{-2e6, 2e6};
  o.range_grows = true;  // said under the bar: "range: grows"
  const Frame want = r.render(quieter, o);
  // Compare the PNG written by the sequence with a frame rendered with the fixed range.
  std::ifstream in(seq.frame_path(1), std::ios::binary);
  const std::vector<unsigned char> png((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(png, encode_png(want.image));
  fs::remove_all(dir);
}

TEST(Sequence, FolderThatCannotBeCreatedIsAnErrorNamingIt) {
  const fs::path dir = temp_dir("seq_bad");
  SequenceOptions so;
  so.folder = unwritable(dir);
  try {
    FrameSequence seq(so);
    FAIL() << "no error";
  } catch (const dda::Error& e) {
    EXPECT_TRUE(contains(e.what(), so.folder.string())) << e.what();
  }
  so.folder = dir;
  so.every_steps = 2;
  so.every_time = 1;
  EXPECT_THROW(FrameSequence{so}, dda::Error) << "both every_steps and every_time";
  fs::remove_all(dir);
}

TEST(Sequence, StopPolicyThrowsAtTheNextCall) {
  const fs::path dir = temp_dir("seq_stop");
  SequenceOptions so;
  so.folder = dir;
  so.frame = small_frame();
  FrameSequence seq(so);
  {
    NoOsmesa off;
    seq.capture(small_scene(0, 0));
    EXPECT_THROW(seq.flush(), dda::Error);
  }
  EXPECT_TRUE(contains(seq.last_error(), "OpenGL context"));
  // The caller chose to go on: later frames work.
  seq.capture(small_scene(1, 0));
  EXPECT_NO_THROW(seq.flush());
  EXPECT_TRUE(fs::exists(seq.frame_path(1)));
  fs::remove_all(dir);
}

TEST(Sequence, ContinuePolicyWarnsOnceAndTheRunGoesOn) {
  const fs::path dir = temp_dir("seq_cont");
  SequenceOptions so;
  so.folder = dir;
  so.frame = small_frame();
  so.on_error = OnError::Continue;
  std::vector<std::string> warnings;
  so.warn = [&](const std::string& m) { warnings.push_back(m); };
  FrameSequence seq(so);
  NoOsmesa off;
  for (long step = 0; step < 6; ++step) {
    EXPECT_NO_THROW(seq.maybe_capture(small_scene(step, 0)));
    while (seq.writer().pending() > 0) std::this_thread::yield();
  }
  EXPECT_NO_THROW(seq.flush());
  EXPECT_FALSE(seq.active());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_TRUE(contains(warnings[0], "OpenGL context")) << warnings[0];
  EXPECT_TRUE(contains(warnings[0], "the run goes on")) << warnings[0];
  fs::remove_all(dir);
}
