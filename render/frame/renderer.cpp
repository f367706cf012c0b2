// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "frame/renderer.hpp"

#include <GL/gl.h>
#include <GL/osmesa.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "frame/triangulate.hpp"
#include "raster/canvas.hpp"
#include "raster/text.hpp"

namespace dda::render {
namespace {

std::atomic<bool> g_osmesa_disabled{false};

// Why a context may not be created now, or nullptr.
const char* osmesa_disabled_reason() {
  if (g_osmesa_disabled.load()) return "OSMesa is disabled by the test hook set_osmesa_disabled_for_testing";
  const char* env = std::getenv("DDA_RENDER_DISABLE_OSMESA");
  if (env && *env && std::string_view(env) != "0") return "OSMesa is disabled by DDA_RENDER_DISABLE_OSMESA";
  return nullptr;
}

constexpr int kMaxSize = 8192;
constexpr Rgb kNoFieldColor{200, 200, 200};
constexpr Rgb kTextColor{20, 20, 20};
constexpr Rgb kContactColor[3] = {{255, 255, 255}, {255, 0, 255}, {0, 0, 0}};  // open, sliding, locked
constexpr const char* kContactName[3] = {"open", "sliding", "locked"};

// Everything about where things go, decided before any drawing.
struct Plan {
  FrameLayout layout;
  const FieldInfo* info = nullptr;
  bool has_field = false;
  float text = 14;  // text size (px)
  int margin = 8;
  Ticks ticks;
  PixelRect panel;   // colour bar + legend area (right)
  PixelRect legend;  // contact legend (inside the panel)
  std::vector<double> values;
  std::string max_text, min_text;  // the frame's extremes under the colour bar
  int arrow = 0;                   // height of the bar's arrow ends (0: no set range)
};

ValueRange auto_range(const std::vector<double>& values, const FieldInfo& info) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, maxabs = 0;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    lo = std::min(lo, v), hi = std::max(hi, v), maxabs = std::max(maxabs, std::abs(v));
  }
  const double unit = 1 / info.display_scale;  // one display unit, in SI
  if (info.is_signed) {
    if (!(maxabs > 0)) maxabs = unit;
    return {-maxabs, maxabs};
  }
  if (!(hi > 0)) hi = unit;
  return {0, hi};
}

// The smallest and largest finite value (both 0 when there is none).
ValueRange data_extremes(const std::vector<double>& values) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : values)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  return lo <= hi ? ValueRange{lo, hi} : ValueRange{0, 0};
}

Box fit_view(const Scene& scene, double magnify) {
  Box b = scene.bounds(magnify);
  if (scene.block_count() == 0) b = {-1, -1, 1, 1};
  double w = b.width(), h = b.height();
  const double size = std::max({w, h, 1e-12});
  if (w < 1e-9 * size) b.xmin -= size / 2, b.xmax += size / 2;
  if (h < 1e-9 * size) b.ymin -= size / 2, b.ymax += size / 2;
  w = b.width(), h = b.height();
  const double pad = 0.04 * std::max(w, h);
  return {b.xmin - pad, b.ymin - pad, b.xmax + pad, b.ymax + pad};
}

// Widens the window in x or y so world units are square in pixels.
Box square_pixels(Box v, const PixelRect& r) {
  const double px_aspect = static_cast<double>(r.w) / r.h, w = v.width(), h = v.height();
  if (w / h < px_aspect) {
    const double nw = h * px_aspect, cx = (v.xmin + v.xmax) / 2;
    v.xmin = cx - nw / 2, v.xmax = cx + nw / 2;
  } else {
    const double nh = w / px_aspect, cy = (v.ymin + v.ymax) / 2;
    v.ymin = cy - nh / 2, v.ymax = cy + nh / 2;
  }
  return v;
}

Plan make_plan(const Scene& scene, const FrameOptions& o) {
  Plan p;
  FrameLayout& L = p.layout;
  L.width = o.width, L.height = o.height;
  p.info = &field_info(o.field);
  p.has_field = o.field != Field::None;
  L.colormap = o.colormap.value_or(default_colormap(o.field));

  const std::size_t n = scene.block_count();
  p.values.resize(n);
  for (std::size_t b = 0; b < n; ++b) p.values[b] = field_value(scene, b, o.field);
  L.range = o.range ? *o.range : auto_range(p.values, *p.info);
  L.data = data_extremes(p.values);
  L.above = o.range && L.data.max > L.range.max;
  L.below = o.range && L.data.min < L.range.min;
  L.range_note = !o.range ? "range: frame" : o.range_grows ? "range: grows" : "range: fixed";

  p.text = std::clamp(o.height / 36.0f, 10.0f, 32.0f);
  p.margin = static_cast<int>(std::lround(p.text * 0.6));
  const int th = text_height(p.text), m = p.margin;
  const int top = o.show_info ? th + 2 * m : m;

  const bool bar = o.show_colorbar && p.has_field;
  int panel_w = 0;
  if (bar) {
    const double scale = p.info->display_scale;
    const int ramp_h_guess = std::max(20, o.height - top - 3 * th - 2 * m);
    p.ticks = nice_ticks(L.range.min * scale, L.range.max * scale, std::clamp(ramp_h_guess / (3 * th), 2, 8));
    int label_w = 0;
    for (const std::string& s : p.ticks.labels) label_w = std::max(label_w, text_width(s, p.text));
    const int ramp_w = static_cast<int>(std::lround(p.text * 1.1));
    panel_w = ramp_w + static_cast<int>(std::lround(p.text * 0.7)) + label_w + m;
    const std::string unit = p.ticks.multiplier.empty() ? p.info->unit : p.ticks.multiplier + " " + p.info->unit;
    p.max_text = "max " + format_number(L.data.max * scale, 3);
    p.min_text = "min " + format_number(L.data.min * scale, 3);
    panel_w =
        std::max({panel_w, text_width(p.info->label, p.text), text_width("[" + unit + "]", p.text),
                  text_width(p.max_text, p.text), text_width(p.min_text, p.text), text_width(L.range_note, p.text)});
    if (o.range) p.arrow = ramp_w;
  }
  if (o.show_contacts) panel_w = std::max(panel_w, th + m / 2 + text_width("sliding", p.text));
  if (o.show_joint_state) panel_w = std::max(panel_w, th + m / 2 + text_width("failed joint", p.text));
  if (panel_w > 0) panel_w += m;

  L.model = {m, top, o.width - 2 * m - panel_w, o.height - top - m};
  if (L.model.w < 8 || L.model.h < 8)
    throw Error(msg("frame ", o.width, "x", o.height, " is too small for its colour bar and text"));
  p.panel = {L.model.right() + m, top, panel_w - m, L.model.h};

  int ramp_bottom = p.panel.bottom();
  const int legend_rows = (o.show_contacts ? 3 : 0) + (o.show_joint_state ? 2 : 0);
  if (legend_rows > 0) {
    const int row = th + 2;
    p.legend = {p.panel.x, p.panel.bottom() - legend_rows * row, p.panel.w, legend_rows * row};
    ramp_bottom = p.legend.y - m;
  }
  if (bar) {
    // Under the ramp: max, min and how the range was chosen (three lines).
    const int ramp_top = top + 2 * th + m / 2 + p.arrow;
    const int below_ramp = 3 * th + m / 2 + p.arrow;
    L.colorbar = {p.panel.x, ramp_top, static_cast<int>(std::lround(p.text * 1.1)),
                  std::max(2, ramp_bottom - ramp_top - th / 2 - below_ramp)};
  }

  L.view = square_pixels(o.view ? *o.view : fit_view(scene, o.magnify), L.model);
  if (o.show_velocity) L.arrow_scale = o.arrow_scale > 0 ? o.arrow_scale : auto_arrow_scale(scene, L.view);
  return p;
}

}  // namespace

Box frame_view(const Scene& scene, double magnify) { return fit_view(scene, magnify); }

double auto_arrow_scale(const Scene& scene, const Box& view) {
  double vmax = 0;
  for (const Vec2& v : scene.velocity)
    if (v.allFinite()) vmax = std::max(vmax, v.norm());
  return vmax > 0 ? 0.06 * std::min(view.width(), view.height()) / vmax : 0;
}

ValueRange frame_range(const Scene& scene, Field field) {
  std::vector<double> values(scene.block_count());
  for (std::size_t b = 0; b < values.size(); ++b) values[b] = field_value(scene, b, field);
  return auto_range(values, field_info(field));
}

void FrameOptions::validate() const {
  if (width < 16 || height < 16 || width > kMaxSize || height > kMaxSize)
    throw Error(msg("frame size ", width, "x", height, " is out of range (16 .. ", kMaxSize, " pixels a side)"));
  if (supersample < 1 || supersample > 4) throw Error(msg("supersample = ", supersample, " must be 1 .. 4"));
  if (static_cast<long>(width) * supersample > 16384 || static_cast<long>(height) * supersample > 16384)
    throw Error(msg("frame ", width, "x", height, " with supersample ", supersample, " exceeds OSMesa's 16384 pixels"));
  if (range && !(std::isfinite(range->min) && std::isfinite(range->max) && range->max > range->min))
    throw Error(msg("colour range [", range->min, ", ", range->max, "] must be finite with min < max"));
  if (view && !(std::isfinite(view->xmin) && std::isfinite(view->xmax) && std::isfinite(view->ymin) &&
                std::isfinite(view->ymax) && view->xmax > view->xmin && view->ymax > view->ymin))
    throw Error(msg("view window [", view->xmin, ", ", view->xmax, "] x [", view->ymin, ", ", view->ymax,
                    "] must be finite with min < max"));
  if (!std::isfinite(magnify)) throw Error(msg("magnify = ", magnify, " must be finite"));
  if (!(edge_width > 0 && edge_width <= 16)) throw Error(msg("edge width ", edge_width, " must be in (0, 16] pixels"));
  if (!(contact_size > 0 && contact_size <= 32))
    throw Error(msg("contact size ", contact_size, " must be in (0, 32] pixels"));
  if (!(arrow_scale >= 0) || !std::isfinite(arrow_scale))
    throw Error(msg("arrow scale ", arrow_scale, " must be >= 0"));
}

struct Renderer::Impl {
  OSMesaContext ctx = nullptr;
  std::vector<std::uint8_t> rgba;
  int bw = 0, bh = 0;
  // Scratch reused from frame to frame.
  std::vector<float> tri_xy, line_xy, point_xy, arrow_xy, failed_xy;
  std::vector<std::uint8_t> tri_rgb, point_rgb;
  std::vector<Vec2> poly;
  std::vector<std::array<int, 3>> tris;

  ~Impl() { drop_context(); }

  void drop_context() {
    if (ctx) OSMesaDestroyContext(ctx);
    ctx = nullptr;
  }

  void bind(int w, int h) {
    if (const char* why = osmesa_disabled_reason()) {
      drop_context();
      throw Error(msg("cannot create an off-screen OpenGL context: ", why));
    }
    if (!ctx) {
      ctx = OSMesaCreateContextExt(OSMESA_RGBA, 0, 0, 0, nullptr);
      if (!ctx)
        throw Error(
            "cannot create an off-screen OpenGL context: OSMesaCreateContextExt failed "
            "(is Mesa's libOSMesa with llvmpipe installed?)");
    }
    if (w != bw || h != bh) {
      rgba.assign(static_cast<std::size_t>(w) * h * 4, 0);
      bw = w, bh = h;
    }
    if (!OSMesaMakeCurrent(ctx, rgba.data(), GL_UNSIGNED_BYTE, w, h)) {
      drop_context();
      throw Error(msg("OSMesaMakeCurrent failed for a ", w, "x", h, " buffer"));
    }
  }

  void unbind() { OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0); }

  void draw_gl(const Scene& scene, const FrameOptions& o, const Plan& p);
  void dedupe_edges(const FrameLayout& L, int k);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> edge_keys;
  std::vector<float> unique_xy;
  Image read_back(const FrameOptions& o) const;
};

void Renderer::Impl::draw_gl(const Scene& scene, const FrameOptions& o, const Plan& p) {
  const FrameLayout& L = p.layout;
  const int k = o.supersample;
  const double cx = (L.view.xmin + L.view.xmax) / 2, cy = (L.view.ymin + L.view.ymax) / 2;
  // Coordinates go to OpenGL as floats relative to the view centre, so
  // models far from the origin keep their precision.
  auto push = [&](std::vector<float>& v, const Vec2& q) {
    v.push_back(static_cast<float>(q.x() - cx));
    v.push_back(static_cast<float>(q.y() - cy));
  };
  const double magnify = o.magnify;
  const std::size_t n = scene.block_count();

  tri_xy.clear(), tri_rgb.clear(), line_xy.clear(), point_xy.clear(), point_rgb.clear(), arrow_xy.clear();
  for (std::size_t b = 0; b < n; ++b) {
    const int v0 = scene.offsets[b], nv = scene.offsets[b + 1] - v0;
    poly.resize(nv);
    for (int i = 0; i < nv; ++i) poly[i] = scene.drawn_vertex(b, v0 + i, magnify);
    const Rgb c = p.has_field ? L.color_of(p.values[b]) : kNoFieldColor;
    tris.clear();
    triangulate(poly, tris);
    for (const auto& t : tris)
      for (int i : t) {
        push(tri_xy, poly[i]);
        tri_rgb.insert(tri_rgb.end(), {c.r, c.g, c.b});
      }
    if (o.show_edges)
      for (int i = 0; i < nv; ++i) push(line_xy, poly[i]), push(line_xy, poly[(i + 1) % nv]);
  }
  if (o.show_edges) dedupe_edges(L, k);
  if (o.show_contacts)
    for (const ContactMark& c : scene.contacts) {
      push(point_xy, scene.drawn_vertex(c.block, scene.offsets[c.block] + c.vertex, magnify));
      const Rgb col = kContactColor[static_cast<int>(c.state)];
      point_rgb.insert(point_rgb.end(), {col.r, col.g, col.b});
    }
  failed_xy.clear();
  if (o.show_joint_state)
    for (const ContactMark& c : scene.contacts) {
      if (!c.failed || c.eblock < 0) continue;
      const int v0 = scene.offsets[c.eblock], nv = scene.offsets[c.eblock + 1] - v0;
      push(failed_xy, scene.drawn_vertex(c.eblock, v0 + c.edge, magnify));
      push(failed_xy, scene.drawn_vertex(c.eblock, v0 + (c.edge + 1) % nv, magnify));
    }
  if (o.show_velocity && n > 0) {
    const double scale = L.arrow_scale;
    const double px = L.view.width() / L.model.w;  // metres per pixel
    for (std::size_t b = 0; b < n && scale > 0; ++b) {
      const Vec2 v = scene.velocity[b];
      if (!v.allFinite()) continue;
      const Vec2 a = scene.drawn_centroid(b, magnify), d = scale * v;
      const double len = d.norm();
      if (len < 1.5 * px) continue;
      const Vec2 tip = a + d, u = d / len, nrm(-u.y(), u.x());
      const double head = std::min(0.3 * len, 10 * px);
      push(arrow_xy, a), push(arrow_xy, tip);
      push(arrow_xy, tip), push(arrow_xy, tip - head * u + 0.45 * head * nrm);
      push(arrow_xy, tip), push(arrow_xy, tip - head * u - 0.45 * head * nrm);
    }
  }

  glDisable(GL_DEPTH_TEST);
  glDisable(GL_DITHER);
  glDisable(GL_BLEND);
  glDisable(GL_LINE_SMOOTH);
  glDisable(GL_POINT_SMOOTH);
  glShadeModel(GL_FLAT);
  glViewport(0, 0, bw, bh);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(o.background.r / 255.0f, o.background.g / 255.0f, o.background.b / 255.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);

  // The model rectangle, in OpenGL's bottom-up pixel rows, at k× size.
  const int gx = L.model.x * k, gy = (L.height - L.model.bottom()) * k, gw = L.model.w * k, gh = L.model.h * k;
  glViewport(gx, gy, gw, gh);
  glEnable(GL_SCISSOR_TEST);
  glScissor(gx, gy, gw, gh);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(L.view.xmin - cx, L.view.xmax - cx, L.view.ymin - cy, L.view.ymax - cy, -1, 1);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();

  glEnableClientState(GL_VERTEX_ARRAY);
  if (!tri_xy.empty()) {
    glEnableClientState(GL_COLOR_ARRAY);
    glVertexPointer(2, GL_FLOAT, 0, tri_xy.data());
    glColorPointer(3, GL_UNSIGNED_BYTE, 0, tri_rgb.data());
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(tri_xy.size() / 2));
    glDisableClientState(GL_COLOR_ARRAY);
  }
  if (!line_xy.empty()) {
    glLineWidth(static_cast<float>(o.edge_width * k));
    glColor3ub(o.edge_color.r, o.edge_color.g, o.edge_color.b);
    glVertexPointer(2, GL_FLOAT, 0, line_xy.data());
    glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(line_xy.size() / 2));
  }
  if (!failed_xy.empty()) {
    glLineWidth(static_cast<float>(std::min(16.0, 2 * o.edge_width) * k));
    glColor3ub(o.failed_joint_color.r, o.failed_joint_color.g, o.failed_joint_color.b);
    glVertexPointer(2, GL_FLOAT, 0, failed_xy.data());
    glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(failed_xy.size() / 2));
  }
  if (!arrow_xy.empty()) {
    glLineWidth(static_cast<float>(k));  // whole pixels: llvmpipe's fast line path
    glColor3ub(0, 0, 0);
    glVertexPointer(2, GL_FLOAT, 0, arrow_xy.data());
    glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(arrow_xy.size() / 2));
  }
  if (!point_xy.empty()) {
    // A dark rim, then the state colour, so white/black markers show on any fill.
    glPointSize(static_cast<float>((o.contact_size + 2) * k));
    glColor3ub(60, 60, 60);
    glVertexPointer(2, GL_FLOAT, 0, point_xy.data());
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(point_xy.size() / 2));
    glPointSize(static_cast<float>(o.contact_size * k));
    glEnableClientState(GL_COLOR_ARRAY);
    glColorPointer(3, GL_UNSIGNED_BYTE, 0, point_rgb.data());
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(point_xy.size() / 2));
    glDisableClientState(GL_COLOR_ARRAY);
  }
  glDisableClientState(GL_VERTEX_ARRAY);
  glFinish();
  if (const GLenum err = glGetError(); err != GL_NO_ERROR)
    throw Error(msg("OpenGL error 0x", std::hex, err, " while drawing a frame"));
}

// Neighbouring blocks share edges, so most edges come twice. llvmpipe pays
// about a microsecond per line, so lines whose ends fall on the same
// half-pixel positions are drawn once (the first in block order: the result
// depends only on the scene). Edges too far off-screen to key are kept.
void Renderer::Impl::dedupe_edges(const FrameLayout& L, int k) {
  const std::size_t n = line_xy.size() / 4;
  if (n < 2) return;
  // Half-pixels of the (supersampled) buffer per metre; line_xy is relative to
  // the view centre, so on-screen keys stay well inside 0 .. 65535.
  const double sx = 2.0 * k * L.model.w / L.view.width(), sy = 2.0 * k * L.model.h / L.view.height();
  constexpr double o = 32768;
  auto q = [](double v, bool& ok) -> std::uint64_t {
    const long r = std::lround(v);
    if (r < 0 || r > 65535) ok = false;
    return static_cast<std::uint64_t>(std::clamp(r, 0L, 65535L));
  };
  edge_keys.clear();
  std::vector<std::uint32_t> keep_always;
  for (std::size_t e = 0; e < n; ++e) {
    const float* l = &line_xy[4 * e];
    bool ok = true;
    std::uint64_t a = (q(l[0] * sx + o, ok) << 16) | q(l[1] * sy + o, ok);
    std::uint64_t b = (q(l[2] * sx + o, ok) << 16) | q(l[3] * sy + o, ok);
    if (!ok) {
      keep_always.push_back(static_cast<std::uint32_t>(e));
      continue;
    }
    if (a > b) std::swap(a, b);
    edge_keys.emplace_back((a << 32) | b, static_cast<std::uint32_t>(e));
  }
  std::sort(edge_keys.begin(), edge_keys.end());
  std::vector<std::uint32_t> kept = std::move(keep_always);
  for (std::size_t i = 0; i < edge_keys.size(); ++i)
    if (i == 0 || edge_keys[i].first != edge_keys[i - 1].first) kept.push_back(edge_keys[i].second);
  std::sort(kept.begin(), kept.end());
  unique_xy.clear();
  for (std::uint32_t e : kept) unique_xy.insert(unique_xy.end(), &line_xy[4 * e], &line_xy[4 * e + 4]);
  line_xy.swap(unique_xy);
}

Image Renderer::Impl::read_back(const FrameOptions& o) const {
  const int w = o.width, h = o.height, k = o.supersample;
  Image img(w, h);
  std::uint8_t* out = img.data();
  if (k == 1) {
    for (int y = 0; y < h; ++y) {
      const std::uint8_t* src = &rgba[static_cast<std::size_t>(h - 1 - y) * w * 4];
      std::uint8_t* dst = out + static_cast<std::size_t>(y) * w * 3;
      for (int x = 0; x < w; ++x, src += 4, dst += 3) dst[0] = src[0], dst[1] = src[1], dst[2] = src[2];
    }
    return img;
  }
  const int kk = k * k;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      int sum[3] = {0, 0, 0};
      for (int j = 0; j < k; ++j) {
        const std::uint8_t* src = &rgba[(static_cast<std::size_t>(bh - 1 - (y * k + j)) * bw + x * k) * 4];
        for (int i = 0; i < k; ++i, src += 4) sum[0] += src[0], sum[1] += src[1], sum[2] += src[2];
      }
      std::uint8_t* dst = out + (static_cast<std::size_t>(y) * w + x) * 3;
      for (int c = 0; c < 3; ++c) dst[c] = static_cast<std::uint8_t>((sum[c] + kk / 2) / kk);
    }
  return img;
}

namespace {

// The largest 1, 2 or 5 × 10^k not above v (v > 0).
double nice_below(double v) {
  const double p = std::pow(10.0, std::floor(std::log10(v)));
  for (double f : {5.0, 2.0, 1.0})
    if (f * p <= v * (1 + 1e-9)) return f * p;
  return p;
}

// Text with a white halo, legible over any colour.
void halo_text(Image& img, int x, int y, const std::string& text, const TextStyle& ts) {
  TextStyle white = ts;
  white.color = {255, 255, 255};
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      if (dx || dy) draw_text(img, x + dx, y + dy, text, white);
  draw_text(img, x, y, text, ts);
}

// Bottom left of the model view: a scale bar of a round length near a fifth
// of the view's width and, with velocity arrows, a reference arrow of a round
// speed, both in the frame's own scale (so they stay put in a sequence with
// a fixed view and arrow scale).
void draw_scale(Image& img, const FrameOptions& o, const Plan& p) {
  const FrameLayout& L = p.layout;
  const int m = p.margin;
  const double px_per_m = L.model.w / L.view.width();
  const double length = nice_below(0.2 * L.view.width());
  const int bar = static_cast<int>(std::lround(length * px_per_m));
  const int x0 = L.model.x + m, y0 = L.model.bottom() - m - 4;
  const TextStyle ts{p.text * 0.85f, kTextColor, Align::Start, Align::End};
  if (bar >= 4) {
    const Rgb black{0, 0, 0}, white{255, 255, 255};
    img.fill_rect({x0 - 1, y0 - 1, bar + 2, 5}, white);
    img.fill_rect({x0, y0, bar, 3}, black);
    img.fill_rect({x0 - 1, y0 - 6, 3, 9}, black);
    img.fill_rect({x0 + bar - 2, y0 - 6, 3, 9}, black);
    halo_text(img, x0, y0 - 8, format_number(length, 3) + " m", ts);
  }
  if (o.show_velocity && L.arrow_scale > 0) {
    // The round speed whose arrow is at most 8 % of the view's width.
    const double speed = nice_below(0.08 * L.view.width() / L.arrow_scale);
    const double len = speed * L.arrow_scale * px_per_m;
    const double ax = x0 + std::max(bar, 0) + 3.0 * m, ay = y0 + 1.5;
    const double head = std::min(0.3 * len, 10.0);
    stroke_line(img, {ax, ay}, {ax + len, ay}, 1.5, {0, 0, 0}, L.model);
    stroke_line(img, {ax + len, ay}, {ax + len - head, ay - 0.45 * head}, 1.5, {0, 0, 0}, L.model);
    stroke_line(img, {ax + len, ay}, {ax + len - head, ay + 0.45 * head}, 1.5, {0, 0, 0}, L.model);
    halo_text(img, static_cast<int>(ax), y0 - 8, format_number(speed, 3) + " m/s", ts);
  }
}

// An arrow end of the colour bar `r` (above it when `up`), `h` pixels
// tall, in the colour of the values beyond that end.
void draw_arrow_end(Image& img, const PixelRect& r, int h, bool up, Rgb color) {
  const double cx = r.x + r.w / 2.0;
  for (int j = 0; j < h; ++j) {
    const double half = r.w / 2.0 * (h - j) / h;  // row j from the bar outward
    const int y = up ? r.y - 2 - j : r.bottom() + 1 + j;
    img.fill_rect({static_cast<int>(std::lround(cx - half)), y, static_cast<int>(std::lround(2 * half)), 1}, color);
  }
  const double base = up ? r.y - 1.5 : r.bottom() + 1.5, tip = up ? r.y - 2.0 - h : r.bottom() + 1.0 + h;
  const PixelRect all{0, 0, img.width(), img.height()};
  stroke_line(img, {r.x - 0.5, base}, {cx, tip}, 1, {90, 90, 90}, all);
  stroke_line(img, {r.x + r.w + 0.5, base}, {cx, tip}, 1, {90, 90, 90}, all);
}

void draw_overlay(Image& img, const Scene& scene, const FrameOptions& o, const Plan& p) {
  const FrameLayout& L = p.layout;
  const int th = text_height(p.text), m = p.margin;
  TextStyle ts{p.text, kTextColor};

  if (o.show_info) {
    std::string left = !o.title.empty() ? o.title : p.has_field ? p.info->description : "blocks";
    if (o.magnify != 1) left += "    deformation ×" + format_number(o.magnify, 4);
    draw_text(img, m, m, left, ts);
    const std::string right = "t = " + format_number(scene.time, 6) + " s    step " + std::to_string(scene.step);
    draw_text(img, o.width - m, m, right, {p.text, kTextColor, Align::End});
  }

  if (!L.colorbar.empty()) {
    const PixelRect& r = L.colorbar;
    for (int j = 0; j < r.h; ++j) {
      const double t = 1.0 - static_cast<double>(j) / (r.h - 1);
      img.fill_rect({r.x, r.y + j, r.w, 1}, color_at(L.colormap, t));
    }
    outline_rect(img, {r.x - 1, r.y - 1, r.w + 2, r.h + 2}, {90, 90, 90});
    const std::string unit = p.ticks.multiplier.empty() ? p.info->unit : p.ticks.multiplier + " " + p.info->unit;
    draw_text(img, r.x, L.model.y, p.info->label, ts);
    draw_text(img, r.x, L.model.y + th, "[" + unit + "]", ts);
    const double scale = p.info->display_scale, lo = L.range.min * scale, hi = L.range.max * scale;
    const int tick = std::max(3, static_cast<int>(std::lround(p.text * 0.3)));
    for (std::size_t i = 0; i < p.ticks.values.size(); ++i) {
      const double v = p.ticks.values[i];
      const int y = r.y + static_cast<int>(std::lround((hi - v) / (hi - lo) * (r.h - 1)));
      img.fill_rect({r.right() + 1, y, tick, 1}, {60, 60, 60});
      draw_text(img, r.right() + tick + m / 2, y, p.ticks.labels[i], {p.text, kTextColor, Align::Start, Align::Center});
    }
    if (L.above) draw_arrow_end(img, r, p.arrow, true, color_at(L.colormap, 1));
    if (L.below) draw_arrow_end(img, r, p.arrow, false, color_at(L.colormap, 0));
    // The frame's own min and max: dark pointers left of the ramp (beside the
    // arrow end when beyond the range), the ramp's colours left whole.
    const int size = std::max(3, m - 2);
    for (const double v : {L.data.min, L.data.max}) {
      const double f = (v * scale - lo) / (hi - lo);
      const int y = f > 1   ? r.y - 2 - p.arrow / 2
                    : f < 0 ? r.bottom() + 1 + p.arrow / 2
                            : r.y + static_cast<int>(std::lround((1 - f) * (r.h - 1)));
      for (int j = -size / 2; j <= size / 2; ++j) {
        const int w = size - 2 * std::abs(j);  // a triangle pointing at the ramp
        img.fill_rect({r.x - 2 - size, y + j, w, 1}, {0, 0, 0});
      }
    }
    int y = r.bottom() + p.arrow + m / 2;
    for (const std::string* line : {&p.max_text, &p.min_text, &L.range_note}) {
      draw_text(img, r.x, y, *line, ts);
      y += th;
    }
  }

  if (!p.legend.empty()) {
    const int row = th + 2, sq = std::max(4, th / 2);
    int y = p.legend.y;
    if (o.show_contacts)
      for (int i = 0; i < 3; ++i, y += row) {
        const PixelRect box{p.legend.x, y + (th - sq) / 2, sq, sq};
        img.fill_rect({box.x - 1, box.y - 1, box.w + 2, box.h + 2}, {60, 60, 60});
        img.fill_rect(box, kContactColor[i]);
        draw_text(img, p.legend.x + sq + m / 2, y, kContactName[i], ts);
      }
    if (o.show_joint_state) {
      const Rgb colors[2] = {o.edge_color, o.failed_joint_color};
      const char* names[2] = {"intact joint", "failed joint"};
      for (int i = 0; i < 2; ++i, y += row) {
        img.fill_rect({p.legend.x, y + th / 2 - 1, sq, i == 0 ? 1 : 3}, colors[i]);
        draw_text(img, p.legend.x + sq + m / 2, y, names[i], ts);
      }
    }
  }

  if (o.show_scale) draw_scale(img, o, p);

  if (o.show_monitors) {
    const double rad = std::max(3.0, p.text * 0.3);
    for (const MonitorMark& mk : scene.monitors) {
      const Vec2 world = mk.position + (o.magnify - 1) * mk.displacement;
      const Vec2 px = L.to_pixel(world);
      if (!L.model.contains(static_cast<int>(px.x()), static_cast<int>(px.y()))) continue;
      std::vector<PointF> circle;
      for (int i = 0; i <= 24; ++i)
        circle.push_back({px.x() + rad * std::cos(i * kPi / 12), px.y() + rad * std::sin(i * kPi / 12)});
      stroke_polyline(img, circle, 3.5, {255, 255, 255}, L.model);
      stroke_polyline(img, circle, 1.5, {0, 0, 0}, L.model);
      if (!mk.name.empty()) {
        const int tx = static_cast<int>(px.x() + rad + 3), ty = static_cast<int>(px.y() - rad - 1);
        // White halo for legibility over any colour.
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
            if (dx || dy)
              draw_text(img, tx + dx, ty + dy, mk.name, {p.text * 0.85f, {255, 255, 255}, Align::Start, Align::End});
        draw_text(img, tx, ty, mk.name, {p.text * 0.85f, kTextColor, Align::Start, Align::End});
      }
    }
  }
}

}  // namespace

Renderer::Renderer() : impl_(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

Frame Renderer::render(const Scene& scene, const FrameOptions& options) {
  options.validate();
  scene.validate();
  Plan plan = make_plan(scene, options);
  const int k = options.supersample;
  impl_->bind(options.width * k, options.height * k);
  struct Unbind {
    Impl* impl;
    ~Unbind() { impl->unbind(); }
  } unbind{impl_.get()};
  impl_->draw_gl(scene, options, plan);
  Frame frame{impl_->read_back(options), plan.layout};
  draw_overlay(frame.image, scene, options, plan);
  return frame;
}

void Renderer::render_to_png(const Scene& scene, const FrameOptions& options, const std::filesystem::path& path) {
  write_png(render(scene, options).image, path);
}

void set_osmesa_disabled_for_testing(bool disabled) { g_osmesa_disabled.store(disabled); }

}  // namespace dda::render
