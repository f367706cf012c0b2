// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "raster/text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <vector>

#define STBTT_STATIC
#define STB_TRUETYPE_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
#include <stb_easy_font.h>
#include <stb_truetype.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace dda::render {
namespace {

// ---- UTF-8 -----------------------------------------------------------------

std::vector<std::uint32_t> decode_utf8(std::string_view s) {
  std::vector<std::uint32_t> out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    int extra = c < 0x80 ? 0 : c < 0xE0 ? 1 : c < 0xF0 ? 2 : 3;
    std::uint32_t cp = extra == 0 ? c : extra == 1 ? (c & 0x1F) : extra == 2 ? (c & 0x0F) : (c & 0x07);
    if (c >= 0x80 && c < 0xC0) extra = 0, cp = '?';  // stray continuation byte
    ++i;
    for (int k = 0; k < extra && i < s.size(); ++k, ++i) cp = (cp << 6) | (static_cast<unsigned char>(s[i]) & 0x3F);
    out.push_back(cp);
  }
  return out;
}

// ASCII spelling of the few non-ASCII characters the renderer writes.
std::string ascii_fallback(std::string_view utf8) {
  std::string out;
  for (std::uint32_t cp : decode_utf8(utf8)) {
    if (cp >= 32 && cp < 127)
      out += static_cast<char>(cp);
    else if (cp == 0x3C3)
      out += 's';  // σ
    else if (cp == 0x3C4)
      out += 't';  // τ
    else if (cp == 0x394)
      out += 'D';  // Δ
    else if (cp == 0x3B5)
      out += 'e';  // ε
    else if (cp == 0x3BC)
      out += 'u';  // μ
    else if (cp == 0xD7)
      out += 'x';  // ×
    else if (cp == 0xB7)
      out += '.';  // ·
    else if (cp == 0x2212)
      out += '-';  // minus sign
    else if (cp == 0x2014 || cp == 0x2013)
      out += '-';
    else if (cp == 0xB0)
      out += "deg";
    else if (cp == 0xB2)
      out += '2';
    else
      out += '?';
  }
  return out;
}

// ---- Fonts -------------------------------------------------------------------

// An 8-bit coverage mask of one line of text.
struct Mask {
  int w = 0, h = 0;
  std::vector<std::uint8_t> a;
};

struct Glyph {
  int w = 0, h = 0, xoff = 0, yoff = 0;
  std::vector<std::uint8_t> bitmap;
};

class FontCache {
 public:
  // Never destroyed: a frame-writer thread may still draw text while exit()
  // runs the destructors of statics (os.exit with frames queued).
  static FontCache& get() {
    static FontCache* cache = new FontCache;
    return *cache;
  }

  std::string description() {
    std::lock_guard lock(mutex_);
    return ttf_ok_ ? path_ : "stb_easy_font";
  }

  int width(std::string_view text, float size) {
    std::lock_guard lock(mutex_);
    if (!ttf_ok_) return easy_width(text, size);
    const float scale = scale_for(size);
    float pen = 0;
    int prev = 0;
    for (std::uint32_t cp : decode_utf8(text)) {
      const int g = stbtt_FindGlyphIndex(&info_, static_cast<int>(cp));
      if (prev) pen += scale * stbtt_GetGlyphKernAdvance(&info_, prev, g);
      int adv = 0, lsb = 0;
      stbtt_GetGlyphHMetrics(&info_, g, &adv, &lsb);
      pen += scale * adv;
      prev = g;
    }
    return static_cast<int>(std::ceil(pen));
  }

  int height(float size) {
    std::lock_guard lock(mutex_);
    if (!ttf_ok_) return easy_scale(size) * 12;
    return static_cast<int>(std::ceil(size));
  }

  Mask render(std::string_view text, float size) {
    std::lock_guard lock(mutex_);
    return ttf_ok_ ? ttf_render(text, size) : easy_render(text, size);
  }

 private:
  FontCache() {
    std::vector<std::string> candidates;
    if (const char* env = std::getenv("DDA_RENDER_FONT"); env && *env) {
      if (std::string_view(env) == "none") return;
      candidates.emplace_back(env);
    }
    candidates.insert(candidates.end(),
                      {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "/usr/share/fonts/TTF/DejaVuSans.ttf",
                       "/usr/share/fonts/dejavu/DejaVuSans.ttf"});
    for (const std::string& p : candidates) {
      std::ifstream in(p, std::ios::binary);
      if (!in) continue;
      ttf_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      if (ttf_.empty()) continue;
      const int offset = stbtt_GetFontOffsetForIndex(ttf_.data(), 0);
      if (offset < 0 || !stbtt_InitFont(&info_, ttf_.data(), offset)) continue;
      stbtt_GetFontVMetrics(&info_, &ascent_, &descent_, &line_gap_);
      path_ = p;
      ttf_ok_ = true;
      return;
    }
  }

  float scale_for(float size) const { return size / static_cast<float>(ascent_ - descent_); }

  const Glyph& glyph(int g, float size) {
    const auto key = std::make_pair(g, static_cast<int>(std::lround(size * 8)));
    auto it = glyphs_.find(key);
    if (it != glyphs_.end()) return it->second;
    Glyph out;
    const float scale = scale_for(size);
    int x0, y0, x1, y1;
    stbtt_GetGlyphBitmapBox(&info_, g, scale, scale, &x0, &y0, &x1, &y1);
    out.w = std::max(0, x1 - x0), out.h = std::max(0, y1 - y0), out.xoff = x0, out.yoff = y0;
    out.bitmap.assign(static_cast<std::size_t>(out.w) * out.h, 0);
    if (out.w > 0 && out.h > 0) stbtt_MakeGlyphBitmap(&info_, out.bitmap.data(), out.w, out.h, out.w, scale, scale, g);
    return glyphs_.emplace(key, std::move(out)).first->second;
  }

  Mask ttf_render(std::string_view text, float size) {
    Mask m;
    const float scale = scale_for(size);
    const std::vector<std::uint32_t> cps = decode_utf8(text);
    // Width without the lock-taking public width().
    float pen = 0;
    int prev = 0;
    std::vector<std::pair<int, float>> placed;
    for (std::uint32_t cp : cps) {
      const int g = stbtt_FindGlyphIndex(&info_, static_cast<int>(cp));
      if (prev) pen += scale * stbtt_GetGlyphKernAdvance(&info_, prev, g);
      placed.emplace_back(g, pen);
      int adv = 0, lsb = 0;
      stbtt_GetGlyphHMetrics(&info_, g, &adv, &lsb);
      pen += scale * adv;
      prev = g;
    }
    m.w = static_cast<int>(std::ceil(pen)) + 1;
    m.h = static_cast<int>(std::ceil(size));
    m.a.assign(static_cast<std::size_t>(m.w) * m.h, 0);
    const int baseline = static_cast<int>(std::lround(ascent_ * scale));
    for (const auto& [g, x] : placed) {
      const Glyph& gl = glyph(g, size);
      const int ox = static_cast<int>(std::lround(x)) + gl.xoff, oy = baseline + gl.yoff;
      for (int j = 0; j < gl.h; ++j) {
        const int y = oy + j;
        if (y < 0 || y >= m.h) continue;
        for (int i = 0; i < gl.w; ++i) {
          const int xx = ox + i;
          if (xx < 0 || xx >= m.w) continue;
          std::uint8_t& dst = m.a[static_cast<std::size_t>(y) * m.w + xx];
          dst = std::max(dst, gl.bitmap[static_cast<std::size_t>(j) * gl.w + i]);
        }
      }
    }
    return m;
  }

  // stb_easy_font: about 12 px a line at scale 1; scaled by whole pixels.
  static int easy_scale(float size) { return std::max(1, static_cast<int>(std::lround(size / 12))); }

  static int easy_width(std::string_view text, float size) {
    std::string s = ascii_fallback(text);
    return stb_easy_font_width(s.data()) * easy_scale(size);
  }

  static Mask easy_render(std::string_view text, float size) {
    std::string s = ascii_fallback(text);
    const int k = easy_scale(size);
    Mask m;
    m.w = stb_easy_font_width(s.data()) * k + 1;
    m.h = 12 * k;
    m.a.assign(static_cast<std::size_t>(m.w) * m.h, 0);
    std::vector<char> buffer(s.size() * 300 + 64);
    struct Vertex {
      float x, y, z;
      unsigned char c[4];
    };
    const int quads = stb_easy_font_print(0, 1, s.data(), nullptr, buffer.data(), static_cast<int>(buffer.size()));
    const auto* v = reinterpret_cast<const Vertex*>(buffer.data());
    for (int q = 0; q < quads; ++q, v += 4) {
      const int x0 = static_cast<int>(std::lround(v[0].x * k)), y0 = static_cast<int>(std::lround(v[0].y * k));
      const int x1 = static_cast<int>(std::lround(v[2].x * k)), y1 = static_cast<int>(std::lround(v[2].y * k));
      for (int y = std::max(0, y0); y < std::min(m.h, y1); ++y)
        for (int x = std::max(0, x0); x < std::min(m.w, x1); ++x) m.a[static_cast<std::size_t>(y) * m.w + x] = 255;
    }
    return m;
  }

  std::mutex mutex_;
  bool ttf_ok_ = false;
  std::string path_;
  std::vector<unsigned char> ttf_;
  stbtt_fontinfo info_{};
  int ascent_ = 0, descent_ = 0, line_gap_ = 0;
  std::map<std::pair<int, int>, Glyph> glyphs_;
};

int anchor(int pos, int extent, Align a) {
  switch (a) {
    case Align::Start:
      return pos;
    case Align::Center:
      return pos - extent / 2;
    case Align::End:
      return pos - extent;
  }
  return pos;
}

}  // namespace

int text_width(std::string_view utf8, float size) { return FontCache::get().width(utf8, size); }
int text_height(float size) { return FontCache::get().height(size); }
std::string font_description() { return FontCache::get().description(); }

void draw_text(Image& image, int x, int y, std::string_view utf8, const TextStyle& style) {
  if (utf8.empty()) return;
  const Mask m = FontCache::get().render(utf8, style.size);
  if (!style.vertical) {
    const int x0 = anchor(x, m.w, style.h), y0 = anchor(y, m.h, style.v);
    for (int j = 0; j < m.h; ++j)
      for (int i = 0; i < m.w; ++i)
        if (const std::uint8_t a = m.a[static_cast<std::size_t>(j) * m.w + i])
          image.blend_pixel(x0 + i, y0 + j, style.color, a / 255.0f);
    return;
  }
  // Rotated 90° anticlockwise: mask column i goes to output row (w-1-i), mask
  // row j to output column j. The rotated box is m.h wide and m.w tall.
  const int x0 = anchor(x, m.h, style.h), y0 = anchor(y, m.w, style.v);
  for (int j = 0; j < m.h; ++j)
    for (int i = 0; i < m.w; ++i)
      if (const std::uint8_t a = m.a[static_cast<std::size_t>(j) * m.w + i])
        image.blend_pixel(x0 + j, y0 + (m.w - 1 - i), style.color, a / 255.0f);
}

}  // namespace dda::render
