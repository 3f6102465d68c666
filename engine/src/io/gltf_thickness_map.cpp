// io/gltf_thickness_map.cpp - rasterising the baked thickness in UV space; see the header.
#include "io/gltf_thickness_map.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace jade::io {

namespace {

double cross2(glm::dvec2 a, glm::dvec2 b) { return a.x * b.y - a.y * b.x; }

bool finite2(glm::vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }

}  // namespace

uint32_t thickness_map_size(const UvTriangles& t)
{
    double area3 = 0.0, area_uv = 0.0;
    std::vector<double> edges;
    for (size_t i = 0; i + 2 < t.indices.size(); i += 3) {
        const uint32_t a = t.indices[i], b = t.indices[i + 1], c = t.indices[i + 2];
        if (!finite2(t.uv[a]) || !finite2(t.uv[b]) || !finite2(t.uv[c])) continue;
        const glm::dvec3 pa(t.positions[a]), pb(t.positions[b]), pc(t.positions[c]);
        area3 += 0.5 * glm::length(glm::cross(pb - pa, pc - pa));
        area_uv += 0.5 * std::abs(cross2(glm::dvec2(t.uv[b]) - glm::dvec2(t.uv[a]),
                                         glm::dvec2(t.uv[c]) - glm::dvec2(t.uv[a])));
        edges.push_back(glm::length(pb - pa)), edges.push_back(glm::length(pc - pb)),
            edges.push_back(glm::length(pa - pc));
    }
    if (!(area_uv > 0.0) || !(area3 > 0.0) || edges.empty() || !std::isfinite(area3 / area_uv)) return 0;
    std::nth_element(edges.begin(), edges.begin() + std::ptrdiff_t(edges.size() / 2), edges.end());
    const double edge = edges[edges.size() / 2];
    if (!(edge > 0.0)) return 0;
    // Mesh units per UV unit, then texels per UV unit for kTexelsPerEdge texels along the edge.
    const double texels = std::sqrt(area3 / area_uv) / edge * kTexelsPerEdge;
    uint32_t size = kMinSize;
    while (size < kMaxSize && double(size) < texels) size *= 2;
    return size;
}

ThicknessMap bake_thickness_map(const UvTriangles& t, uint32_t size)
{
    ThicknessMap map;
    map.size = size;
    for (float v : t.thickness) map.factor = std::max(map.factor, double(v));
    const size_t n = size_t(size) * size;
    std::vector<double> value(n, 0.0);
    map.covered.assign(n, 0);
    for (size_t i = 0; i + 2 < t.indices.size(); i += 3) {
        const uint32_t k[3] = {t.indices[i], t.indices[i + 1], t.indices[i + 2]};
        if (!finite2(t.uv[k[0]]) || !finite2(t.uv[k[1]]) || !finite2(t.uv[k[2]])) continue;
        glm::dvec2 p[3];  // in texels
        for (int c = 0; c < 3; ++c) p[c] = glm::dvec2(t.uv[k[c]]) * double(size);
        const double area = cross2(p[1] - p[0], p[2] - p[0]);
        if (area == 0.0) continue;
        const glm::dvec2 lo = glm::min(p[0], glm::min(p[1], p[2])), hi = glm::max(p[0], glm::max(p[1], p[2]));
        // Texel centres (x + ½, y + ½) inside the box; one that spans more than the whole texture
        // is cut to one period (its texels repeat).
        const double x0 = std::ceil(lo.x - 0.5), y0 = std::ceil(lo.y - 0.5);
        const double x1 = std::min(std::floor(hi.x - 0.5), x0 + size - 1);
        const double y1 = std::min(std::floor(hi.y - 0.5), y0 + size - 1);
        for (double y = y0; y <= y1; ++y)
            for (double x = x0; x <= x1; ++x) {
                const glm::dvec2 q(x + 0.5, y + 0.5);
                // Barycentric weights; a centre on an edge belongs to both triangles (either value).
                const double w0 = cross2(p[1] - q, p[2] - q) / area, w1 = cross2(p[2] - q, p[0] - q) / area;
                const double w2 = 1.0 - w0 - w1;
                if (w0 < 0.0 || w1 < 0.0 || w2 < 0.0) continue;
                const auto wrap = [size](double v) {
                    const double m = std::fmod(v, double(size));
                    return size_t(m < 0.0 ? m + size : m);
                };
                const size_t texel = wrap(y) * size + wrap(x);
                value[texel] = w0 * t.thickness[k[0]] + w1 * t.thickness[k[1]] + w2 * t.thickness[k[2]];
                map.covered[texel] = 1;
            }
    }
    // Dilation: bilinear filtering and mipmaps at a UV seam read texels just outside the
    // triangles; give them the mean of their covered (or already grown) 8-neighbours.
    std::vector<uint8_t> known = map.covered;
    for (int pass = 0; pass < kDilation; ++pass) {
        std::vector<uint8_t> next = known;
        std::vector<double> grown = value;
        for (uint32_t y = 0; y < size; ++y)
            for (uint32_t x = 0; x < size; ++x) {
                if (known[size_t(y) * size + x]) continue;
                double sum = 0.0;
                int count = 0;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int xx = int(x) + dx, yy = int(y) + dy;
                        if (xx < 0 || yy < 0 || xx >= int(size) || yy >= int(size)) continue;
                        if (known[size_t(yy) * size + size_t(xx)])
                            sum += value[size_t(yy) * size + size_t(xx)], ++count;
                    }
                if (count) grown[size_t(y) * size + x] = sum / count, next[size_t(y) * size + x] = 1;
            }
        value.swap(grown);
        known.swap(next);
    }
    map.texels.resize(n);
    for (size_t i = 0; i < n; ++i)
        map.texels[i] =
            map.factor > 0.0 ? uint8_t(std::lround(std::clamp(value[i] / map.factor, 0.0, 1.0) * 255.0)) : 0;
    return map;
}

}  // namespace jade::io
