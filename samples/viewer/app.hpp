// samples/viewer - the viewer's frame loop: input, panel, Jade's draw, blit, present, and the
// headless-friendly options (--frames, --screenshot) the Xvfb test and the docs use.
#pragma once

#include "scene.hpp"

#include <cstdint>
#include <string>

namespace samples::viewer {

struct Options {
    std::string mesh = "bunny";  ///< file, "bunny" or "sphere"
    uint32_t width = 800, height = 600;
    uint32_t frames = 0;      ///< render this many frames then exit (0: until the window closes)
    std::string screenshot;   ///< write the last presented frame here (.png, .exr)
    bool ui = true;           ///< draw the ImGui panel
    bool validation = false;  ///< VK_LAYER_KHRONOS_validation (also JADE_VALIDATION=1)
    bool vsync = true;        ///< FIFO presentation; false: IMMEDIATE/MAILBOX when available
    uint32_t samples = 4;     ///< MSAA samples of Jade's draw (as `jade render`)
    ViewState state;          ///< the initial settings
};

/// Runs the viewer. Returns the exit status: 0, or 2 when the validation layer reported
/// anything. Throws std::exception (jade::Error included) on errors.
int run(const Options& options);

}  // namespace samples::viewer
