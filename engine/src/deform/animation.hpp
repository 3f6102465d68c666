// deform/animation.hpp - the glTF sampling behind evaluate_pose (jade/deform.hpp), for
// deform/animation.cpp and the glTF reader's checks (io/gltf_animation.cpp). Private to the engine.
#pragma once

#include <jade/deform.hpp>

#include <glm/mat4x4.hpp>

#include <vector>

namespace jade::deform {

/// The channel at time t (clamped to the first and last key): LINEAR interpolates
/// component-wise, rotations by slerp (shortest arc); STEP holds the key at or before t;
/// CUBICSPLINE is glTF's cubic Hermite with tangents scaled by the key interval (rotations are
/// normalised afterwards). Returns `width` floats.
std::vector<float> sample(const AnimationChannel& channel, double t);

/// The node's local transform: its matrix, or translation · rotation · scale.
glm::mat4 local_transform(const AnimatedNode& node);

}  // namespace jade::deform
