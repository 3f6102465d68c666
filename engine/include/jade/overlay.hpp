// jade/overlay.hpp - text drawn into a RenderedImage on the host, for figures and tools (the
// CLI's labelled panels). Not needed to embed the renderer. Part of the core library jade::jade.
#pragma once

#include <jade/render.hpp>

#include <glm/vec3.hpp>

#include <string_view>

namespace jade {

/// Draws ASCII text (a built-in 5×7 pixel font, scaled by `scale`) with its top-left corner at
/// (x, y), clipped to the image. Unknown characters draw as a box.
void draw_text(RenderedImage& image, int x, int y, std::string_view text, glm::vec3 color, int scale = 1);
/// Width in pixels of `text` drawn by draw_text.
int text_width(std::string_view text, int scale = 1);

}  // namespace jade
