#include "engine/render/image_text.hpp"

#include <fmt/format.h>
#include <stb_truetype.h>

#include <cmath>
#include <fstream>
#include <iterator>

#include "engine/core/error.hpp"

namespace pbf {

namespace {

constexpr const char* kFontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

// Unicode codepoints of UTF-8 text; a byte that starts no valid sequence reads as U+FFFD.
std::vector<int> utf8_codepoints(const std::string& text) {
  std::vector<int> out;
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char lead = static_cast<unsigned char>(text[i]);
    const std::size_t length = lead < 0x80         ? 1
                               : (lead >> 5) == 6  ? 2
                               : (lead >> 4) == 14 ? 3
                               : (lead >> 3) == 30 ? 4
                                                   : 0;
    if (length == 0 || i + length > text.size()) {
      out.push_back(0xFFFD), ++i;
      continue;
    }
    int cp = length == 1 ? lead : lead & (0x7F >> length);
    for (std::size_t k = 1; k < length; ++k) cp = (cp << 6) | (static_cast<unsigned char>(text[i + k]) & 0x3F);
    out.push_back(cp), i += length;
  }
  return out;
}

}  // namespace

// Blends colour over pixel (x, y) with coverage alpha in [0, 1]; pixels outside are ignored.
void blend(std::vector<unsigned char>& rgb, int width, int height, int x, int y, const Rgb& colour, float alpha) {
  if (x < 0 || x >= width || y < 0 || y >= height) return;
  unsigned char* p = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
  for (int c = 0; c < 3; ++c) p[c] = static_cast<unsigned char>(std::lround(p[c] + alpha * (colour[c] - p[c])));
}

TextRenderer::TextRenderer(int size_px) : info_(std::make_unique<stbtt_fontinfo>()), pixels_(size_px) {
  std::ifstream in(kFontPath, std::ios::binary);
  if (!in)
    throw Error(
        fmt::format("image: cannot read the font {} (install the Debian package fonts-dejavu-core)", kFontPath));
  ttf_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (!stbtt_InitFont(info_.get(), ttf_.data(), stbtt_GetFontOffsetForIndex(ttf_.data(), 0)))
    throw Error(fmt::format("image: {} is not a TrueType font (reinstall fonts-dejavu-core)", kFontPath));
  scale_ = stbtt_ScaleForPixelHeight(info_.get(), static_cast<float>(size_px));
  int asc = 0, desc = 0, gap = 0;
  stbtt_GetFontVMetrics(info_.get(), &asc, &desc, &gap);
  ascent_ = static_cast<int>(std::lround(asc * scale_));
  for (int cp = 32; cp < 127; ++cp) ascii_.push_back(rasterise(cp));
}

TextRenderer::~TextRenderer() = default;

TextRenderer::Glyph TextRenderer::rasterise(int codepoint) const {
  Glyph g;
  unsigned char* bitmap = stbtt_GetCodepointBitmap(info_.get(), 0, scale_, codepoint, &g.w, &g.h, &g.x0, &g.y0);
  if (bitmap) g.alpha.assign(bitmap, bitmap + static_cast<std::size_t>(g.w) * g.h);
  stbtt_FreeBitmap(bitmap, nullptr);
  return g;
}

float TextRenderer::advance(int codepoint, int next) const {
  int advance_units = 0, left_bearing = 0;
  stbtt_GetCodepointHMetrics(info_.get(), codepoint, &advance_units, &left_bearing);
  const int kern = next ? stbtt_GetCodepointKernAdvance(info_.get(), codepoint, next) : 0;
  return scale_ * static_cast<float>(advance_units + kern);
}

int TextRenderer::width(const std::string& text) const {
  const auto cps = utf8_codepoints(text);
  float pen = 0;
  for (std::size_t k = 0; k < cps.size(); ++k) pen += advance(cps[k], k + 1 < cps.size() ? cps[k + 1] : 0);
  return static_cast<int>(std::ceil(pen));
}

void TextRenderer::draw(std::vector<unsigned char>& rgb, int width, int height, int x, int y, const std::string& text,
                      const Rgb& colour) const {
  const auto cps = utf8_codepoints(text);
  float pen = static_cast<float>(x);
  for (std::size_t k = 0; k < cps.size(); ++k) {
    const int cp = cps[k];
    const Glyph uncached = cp >= 32 && cp < 127 ? Glyph{} : rasterise(cp);
    const Glyph& g = cp >= 32 && cp < 127 ? ascii_[cp - 32] : uncached;
    const int gx = static_cast<int>(std::lround(pen)) + g.x0, gy = y + g.y0;
    for (int row = 0; row < g.h; ++row)
      for (int col = 0; col < g.w; ++col) {
        const unsigned char a = g.alpha[static_cast<std::size_t>(row) * g.w + col];
        if (a) blend(rgb, width, height, gx + col, gy + row, colour, a / 255.0f);
      }
    pen += advance(cp, k + 1 < cps.size() ? cps[k + 1] : 0);
  }
}

}  // namespace pbf
