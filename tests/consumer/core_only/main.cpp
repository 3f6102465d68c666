// Links the core library alone and uses the LUT reference and a procedural mesh (no device).
#include <jade/lut.hpp>
#include <jade/mesh.hpp>

#include <cstdio>

int main()
{
    const jade::PreparedMesh sphere = jade::prepare_mesh(jade::procedural::sphere(1.0f, 8, 12));
    // f(θ, 0) is Lambert: max(cos θ, 0) / π... as the LUT stores it; print and check its sign.
    const double f = jade::lut_reference(0.5, 0.0);
    std::printf("core_consumer: %zu vertices, f(60 deg, 0) = %g\n", sphere.vertex_count(), f);
    return sphere.vertex_count() > 0 && f > 0.0 ? 0 : 1;
}
