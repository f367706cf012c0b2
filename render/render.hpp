// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The renderer's public API in one include.
//
//   scene/scene.hpp          Scene: plain data a frame shows (blocks, values, contacts, monitors)
//   scene/field.hpp          Field: sigma_xx, sigma_yy, tau_xy, sigma_1, von_mises, velocity, displacement
//   scene/world_scene.hpp    WorldSnapshot / snapshot(): Scene from a dda::World; write_frame(): one frame now
//   frame/renderer.hpp       Renderer, FrameOptions, Frame, FrameLayout: OSMesa frames
//   output/frame_sequence.hpp FrameSequence: numbered frames every N steps or Δt, async
//   output/frame_writer.hpp  FrameWriter: the bounded queue + worker thread behind it
//   plot/plot.hpp            PlotSpec, render_plot, write_plot_png: history line plots
//   raster/image.hpp         Image, Rgb, write_png
//   raster/colormap.hpp      ColorMap (viridis, coolwarm), color_at
#include "frame/renderer.hpp"
#include "output/frame_sequence.hpp"
#include "output/frame_writer.hpp"
#include "plot/plot.hpp"
#include "raster/colormap.hpp"
#include "raster/image.hpp"
#include "scene/field.hpp"
#include "scene/scene.hpp"
#include "scene/world_scene.hpp"
