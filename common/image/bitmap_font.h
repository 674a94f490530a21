#ifndef EVOSLAM_COMMON_IMAGE_BITMAP_FONT_H_
#define EVOSLAM_COMMON_IMAGE_BITMAP_FONT_H_

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/image/image.h"

namespace evoslam {

// A built-in bitmap font for printable ASCII, so that pictures can carry words without a font
// library. Each glyph is 5 pixels wide and 9 high (7 above the baseline, 2 for descenders) in a
// cell of kGlyphAdvance x kLineAdvance; `scale` draws every font pixel as a scale x scale block.
// Any other byte is drawn as '?'.
inline constexpr int kGlyphWidth = 5;
inline constexpr int kGlyphHeight = 9;
inline constexpr int kGlyphAdvance = 6;
inline constexpr int kLineAdvance = 11;
// The capitals' height above the baseline, which marks and numbers beside text are centred on.
inline constexpr int kCapitalHeight = 7;

// Pixels from the first glyph's left edge to the last one's right edge; 0 for no text.
int TextWidth(std::string_view text, int scale = 1);
// Pixels from the top of a line to the bottom of its descenders.
inline int TextHeight(int scale = 1) { return kGlyphHeight * scale; }

// Draws the text with its first glyph's top-left pixel at (x, y), clipped to the image.
void DrawText(Image& image, int x, int y, std::string_view text, Rgb color, int scale = 1);

// The text broken at spaces into lines of at most `max_width` pixels; a word wider than that is
// cut between glyphs. At least one line, empty for no text.
std::vector<std::string> WrapText(std::string_view text, int max_width, int scale = 1);

// The top-left pixel of the first place, in reading order, where the image shows the text as
// DrawText draws it in `color`: the glyphs' pixels in that colour and no other pixel of their
// cells. For checking that a picture says what it should.
std::optional<Eigen::Vector2i> FindText(const Image& image, std::string_view text, Rgb color,
                                        int scale = 1);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_IMAGE_BITMAP_FONT_H_
