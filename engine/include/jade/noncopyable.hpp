// jade/noncopyable.hpp - the base of the classes that must have one owner.
#pragma once

namespace jade {

/// Derive from this (privately) to delete the copy constructor and copy assignment: a Context,
/// Baker, Renderer and the other classes that own GPU objects, or the host's device set-up that
/// AdoptedVulkan points into, have exactly one owner. A derived class declares no move either,
/// so it stays where it was constructed.
class NonCopyable {
public:
    NonCopyable(const NonCopyable&) = delete;
    NonCopyable& operator=(const NonCopyable&) = delete;

protected:
    NonCopyable() = default;
    ~NonCopyable() = default;
};

}  // namespace jade
