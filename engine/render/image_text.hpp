#pragma once
// Text in images: DejaVu Sans (Debian's fonts-dejavu-core) through stb_truetype, at one
// pixel size per TextRenderer; printable ASCII is rasterised once when it is made, other
// characters when drawn. Antialiased: glyph coverage is blended over the pixels.
#include <memory>
#include <string>
#include <vector>

#include "engine/render/colormap.hpp"

struct stbtt_fontinfo;

namespace pbf {

// Blends colour over pixel (x, y) of an RGB image with coverage alpha in [0, 1]; pixels
// outside the image are ignored.
void blend(std::vector<unsigned char>& rgb, int width, int height, int x, int y, const Rgb& colour, float alpha);

class TextRenderer {
 public:
  // Loads the font; a missing or broken file is a pbf::Error naming it and its package.
  explicit TextRenderer(int size_px);
  ~TextRenderer();
  TextRenderer(const TextRenderer&) = delete;  // the font info points into the file's bytes
  TextRenderer& operator=(const TextRenderer&) = delete;

  int pixels() const { return pixels_; }  // the font size: ascent minus descent
  int ascent() const { return ascent_; }  // pixels above the baseline
  // The width of UTF-8 text in pixels.
  int width(const std::string& text) const;
  // Draws UTF-8 text with its baseline at y, starting at x; clipped to the image.
  void draw(std::vector<unsigned char>& rgb, int width, int height, int x, int y, const std::string& text,
            const Rgb& colour) const;

 private:
  struct Glyph {
    int x0 = 0, y0 = 0, w = 0, h = 0;  // bitmap offset from the pen position on the baseline
    std::vector<unsigned char> alpha;  // w*h coverage, row-major
  };
  Glyph rasterise(int codepoint) const;
  float advance(int codepoint, int next) const;

  std::vector<unsigned char> ttf_;  // the file; info_ points into it
  std::unique_ptr<stbtt_fontinfo> info_;
  float scale_ = 0;  // font units to pixels
  int pixels_ = 0, ascent_ = 0;
  std::vector<Glyph> ascii_;  // codepoints 32..126
};

}  // namespace pbf
