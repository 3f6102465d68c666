// jade/error.hpp - the one exception type thrown across Jade's public API.
#pragma once

#include <stdexcept>
#include <string>

namespace jade {

/// Every failure Jade reports to its caller: bad input files, bad parameters, a missing or
/// unsuitable Vulkan device, a failed Vulkan call. The message is complete and names the
/// subject first (a file, a flag, an element), e.g.
///   "bunny.glb: accessor 3 (indices): index 40912 out of range for 37706 vertices".
/// Programmer mistakes inside Jade are asserts, never Errors.
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace jade
