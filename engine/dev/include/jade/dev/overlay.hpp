// jade/dev/overlay.hpp - what is drawn into a RenderedImage on the host, for figures and tools:
// text (the CLI's labelled panels), tone mapping, the false-colour map and its colour bar.
// Renderer::render applies the last three itself. Declared for jade::dev, defined in jade::jade.
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

/// The host-side finish of Renderer::render (and SceneRenderer::render), for images read back
/// another way too: tone mapping, and the false-colour map with its legend.
void apply_tone_map(RenderedImage& image, ToneMap tone_map, float exposure = 1.0f);
/// The colour map of TmFalseColor (viridis), linear RGB, for x in [0, 1].
glm::vec3 false_color(float x);
/// Draws the TmFalseColor colour bar, labelled `min_value` at the bottom and `max_value` at the
/// top, at the right edge of the image.
void draw_color_bar(RenderedImage& image, float min_value, float max_value, std::string_view title = "t_m");

}  // namespace jade
