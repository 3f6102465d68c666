// io/ply.cpp - PLY reader: ASCII, binary little-endian and binary big-endian.
//
// The "vertex" element must have scalar x, y, z properties (any numeric type, any order); nx, ny,
// nz are read when all three are present. The "face" element must have a list property
// "vertex_indices" (or "vertex_index") of an integer type; polygons are fan-triangulated. Every
// other property, element and list is skipped. Header counts are checked against the bytes
// after the header (cumulatively, element by element) before anything is allocated.
#include "io/loaders.hpp"
#include "io/text_reader.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <optional>

namespace jade::io {

namespace {

enum class Type : uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<Type> parse_type(std::string_view s)
{
    static constexpr std::array<std::pair<std::string_view, Type>, 16> kNames{{
        {"char", Type::Int8},
        {"int8", Type::Int8},
        {"uchar", Type::UInt8},
        {"uint8", Type::UInt8},
        {"short", Type::Int16},
        {"int16", Type::Int16},
        {"ushort", Type::UInt16},
        {"uint16", Type::UInt16},
        {"int", Type::Int32},
        {"int32", Type::Int32},
        {"uint", Type::UInt32},
        {"uint32", Type::UInt32},
        {"float", Type::Float32},
        {"float32", Type::Float32},
        {"double", Type::Float64},
        {"float64", Type::Float64},
    }};
    for (const auto& [name, type] : kNames)
        if (name == s) return type;
    return std::nullopt;
}

size_t type_size(Type t)
{
    switch (t) {
    case Type::Int8:
    case Type::UInt8: return 1;
    case Type::Int16:
    case Type::UInt16: return 2;
    case Type::Int32:
    case Type::UInt32:
    case Type::Float32: return 4;
    case Type::Float64: return 8;
    }
    return 0;
}

bool is_integer(Type t) { return t != Type::Float32 && t != Type::Float64; }

struct Property {
    std::string name;
    Type type = Type::Float32;  ///< the value type, or the item type of a list
    bool list = false;
    Type count_type = Type::UInt8;
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> properties;
    std::string value_what;  ///< "value of <name>", for ASCII parse messages
};

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct Header {
    Format format = Format::Ascii;
    std::vector<Element> elements;
    size_t body_offset = 0;  ///< first byte after "end_header\n"
    size_t body_line = 0;    ///< line number of that byte
};

/// Where the properties the reader uses sit in their elements (indices into `properties`).
struct Layout {
    const Element* vertex = nullptr;
    const Element* face = nullptr;
    int x = -1, y = -1, z = -1, nx = -1, ny = -1, nz = -1;
    int indices = -1;
};

// ---------------------------------------------------------------------------------- header --

std::vector<std::string_view> split_words(std::string_view line)
{
    std::vector<std::string_view> words;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        const size_t begin = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
        if (i > begin) words.push_back(line.substr(begin, i - begin));
    }
    return words;
}

class HeaderParser {
public:
    HeaderParser(const std::string& file, std::string_view bytes) : file_(file), bytes_(bytes) {}

    Header parse()
    {
        if (split_words(next_line()) != std::vector<std::string_view>{"ply"})
            fail_line("not a PLY file (no 'ply' magic line)");
        bool have_format = false;
        for (;;) {
            const auto w = split_words(next_line());
            if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
            if (w[0] == "end_header") break;
            if (w[0] == "format") {
                parse_format(w);
                have_format = true;
            } else if (w[0] == "element") {
                parse_element(w);
            } else if (w[0] == "property") {
                parse_property(w);
            } else {
                fail_line("unknown header keyword '" + printable(w[0]) + "'");
            }
        }
        if (!have_format) fail_line("the header has no 'format' line");
        header_.body_offset = pos_;
        header_.body_line = line_ + 1;
        return std::move(header_);
    }

private:
    std::string_view next_line()
    {
        const size_t end = bytes_.find('\n', pos_);
        if (end == std::string_view::npos) fail(file_, "the header has no 'end_header' line");
        auto line = bytes_.substr(pos_, end - pos_);
        pos_ = end + 1;
        ++line_;
        return line;
    }

    [[noreturn]] void fail_line(const std::string& what) const
    {
        fail(file_, "line " + std::to_string(line_) + ": " + what);
    }

    void parse_format(const std::vector<std::string_view>& w)
    {
        if (w.size() != 3) fail_line("expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
        if (w[1] == "ascii")
            header_.format = Format::Ascii;
        else if (w[1] == "binary_little_endian")
            header_.format = Format::BinaryLittleEndian;
        else if (w[1] == "binary_big_endian")
            header_.format = Format::BinaryBigEndian;
        else
            fail_line("format '" + printable(w[1]) +
                      "' is not supported (ascii, binary_little_endian, binary_big_endian)");
    }

    void parse_element(const std::vector<std::string_view>& w)
    {
        if (w.size() != 3) fail_line("expected 'element <name> <count>'");
        Element e;
        e.name = printable(w[1]);  // element names appear in every message about the element
        e.value_what = "value of " + e.name;
        auto [end, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
        if (ec != std::errc() || end != w[2].data() + w[2].size())
            fail_line("element '" + e.name + "': count '" + printable(w[2]) + "' is not a non-negative integer");
        header_.elements.push_back(std::move(e));
    }

    Type type_of(std::string_view word) const
    {
        auto t = parse_type(word);
        if (!t) fail_line("unknown property type '" + printable(word) + "'");
        return *t;
    }

    void parse_property(const std::vector<std::string_view>& w)
    {
        if (header_.elements.empty()) fail_line("property before any element");
        Property p;
        if (w.size() == 5 && w[1] == "list") {
            p.list = true;
            p.count_type = type_of(w[2]);
            p.type = type_of(w[3]);
            p.name = std::string(w[4]);
            if (!is_integer(p.count_type))
                fail_line("list '" + printable(p.name) + "': the count type must be an integer type");
        } else if (w.size() == 3) {
            p.type = type_of(w[1]);
            p.name = std::string(w[2]);
        } else {
            fail_line("expected 'property <type> <name>' or 'property list <count type> <type> <name>'");
        }
        header_.elements.back().properties.push_back(std::move(p));
    }

    const std::string& file_;
    std::string_view bytes_;
    size_t pos_ = 0, line_ = 0;
    Header header_;
};

int find_property(const Element& e, std::string_view name, bool list)
{
    for (size_t i = 0; i < e.properties.size(); ++i)
        if (e.properties[i].name == name && e.properties[i].list == list) return static_cast<int>(i);
    return -1;
}

Layout find_layout(const std::string& file, const Header& h)
{
    Layout l;
    for (const auto& e : h.elements) {
        if (e.name == "vertex" && !l.vertex) l.vertex = &e;
        if (e.name == "face" && !l.face) l.face = &e;
    }
    if (!l.vertex) fail(file, "no 'vertex' element");
    if (!l.face) fail(file, "no 'face' element (a point cloud is not a mesh)");
    int* coords[3] = {&l.x, &l.y, &l.z};
    for (int c = 0; c < 3; ++c) {
        const char name[2] = {char('x' + c), 0};
        *coords[c] = find_property(*l.vertex, name, false);
        if (*coords[c] < 0) fail(file, std::string("element 'vertex' has no scalar property '") + name + "'");
    }
    l.nx = find_property(*l.vertex, "nx", false);
    l.ny = find_property(*l.vertex, "ny", false);
    l.nz = find_property(*l.vertex, "nz", false);
    l.indices = find_property(*l.face, "vertex_indices", true);
    if (l.indices < 0) l.indices = find_property(*l.face, "vertex_index", true);
    if (l.indices < 0) fail(file, "element 'face' has no list property 'vertex_indices' (or 'vertex_index')");
    if (!is_integer(l.face->properties[size_t(l.indices)].type))
        fail(file, "face list '" + printable(l.face->properties[size_t(l.indices)].name) +
                       "' must have an integer item type");
    return l;
}

/// The fewest bytes one element can take: lists empty, except faces which need 3 indices. In
/// ASCII every value takes at least a digit and a separator.
uint64_t min_element_bytes(const Element& e, const Layout& l, bool ascii)
{
    uint64_t bytes = 0, values = 0;
    for (size_t i = 0; i < e.properties.size(); ++i) {
        const auto& p = e.properties[i];
        const uint64_t items = (&e == l.face && int(i) == l.indices) ? 3 : 0;
        bytes += p.list ? type_size(p.count_type) + items * type_size(p.type) : type_size(p.type);
        values += p.list ? 1 + items : 1;
    }
    return ascii ? 2 * values : bytes;
}

void check_counts(const std::string& file, const Header& h, const Layout& l, uint64_t body_bytes)
{
    const bool ascii = h.format == Format::Ascii;
    uint64_t left = body_bytes + (ascii ? 1 : 0);  // the last ASCII value needs no separator
    for (const auto& e : h.elements) {
        if (e.count > 0 && e.properties.empty()) fail(file, "element '" + e.name + "' has no properties");
        const uint64_t each = min_element_bytes(e, l, ascii);
        check_count(file, "'" + e.name + "' elements", e.count, each, left);
        left -= e.count * each;
    }
}

// ---------------------------------------------------------------------------------- values --

/// Reads values from a binary body, in either byte order. Errors name the byte offset.
class BinarySource {
public:
    BinarySource(const std::string& file, std::string_view body, size_t body_offset, bool big_endian)
        : file_(file), body_(body), offset_(body_offset), swap_(big_endian)
    {
    }

    void begin(const Element& e, uint64_t index) { element_ = &e, index_ = index; }

    double scalar(Type t)
    {
        switch (t) {
        case Type::Float32: return read<float>();
        case Type::Float64: return read<double>();
        default: return static_cast<double>(integer(t));
        }
    }

    int64_t integer(Type t)
    {
        switch (t) {
        case Type::Int8: return read<int8_t>();
        case Type::UInt8: return read<uint8_t>();
        case Type::Int16: return read<int16_t>();
        case Type::UInt16: return read<uint16_t>();
        case Type::Int32: return read<int32_t>();
        case Type::UInt32: return read<uint32_t>();
        default: return static_cast<int64_t>(scalar(t));  // not reached: the header checks list types
        }
    }

    void skip(Type t) { skip_bytes(type_size(t)); }
    void skip_list(Type count_type, Type item_type)
    {
        const int64_t n = integer(count_type);
        if (n < 0) fail("negative list length " + std::to_string(n));
        if (uint64_t(n) > (body_.size() - pos_) / type_size(item_type)) eof();
        skip_bytes(size_t(n) * type_size(item_type));
    }

    [[noreturn]] void fail(const std::string& what) const
    {
        io::fail(file_, "byte " + std::to_string(offset_ + pos_) + ": " + element_->name + " " +
                            std::to_string(index_) + ": " + what);
    }

private:
    [[noreturn]] void eof() const
    {
        io::fail(file_, "byte " + std::to_string(offset_ + pos_) + ": unexpected end of file in " + element_->name +
                            " " + std::to_string(index_) + " of " + std::to_string(element_->count));
    }

    void skip_bytes(size_t n)
    {
        if (body_.size() - pos_ < n) eof();
        pos_ += n;
    }

    template <class T> T read()
    {
        if (body_.size() - pos_ < sizeof(T)) eof();
        std::array<char, sizeof(T)> raw;
        std::memcpy(raw.data(), body_.data() + pos_, sizeof(T));
        if (swap_) std::reverse(raw.begin(), raw.end());
        pos_ += sizeof(T);
        T v;
        std::memcpy(&v, raw.data(), sizeof(T));
        return v;
    }

    const std::string& file_;
    std::string_view body_;
    size_t offset_, pos_ = 0;
    bool swap_;
    const Element* element_ = nullptr;
    uint64_t index_ = 0;
};

/// Reads values from an ASCII body. Errors name the line.
class AsciiSource {
public:
    AsciiSource(const std::string& file, std::string_view body, size_t first_line) : in_(file, body, first_line, false)
    {
    }

    void begin(const Element& e, uint64_t index) { element_ = &e, index_ = index; }
    double scalar(Type) { return in_.real(what()); }
    int64_t integer(Type) { return in_.integer(what()); }
    void skip(Type) { in_.token(what()); }
    void skip_list(Type, Type)
    {
        const int64_t n = in_.integer(what());
        if (n < 0) fail("negative list length " + std::to_string(n));
        for (int64_t i = 0; i < n; ++i) in_.token(what());
    }
    [[noreturn]] void fail(const std::string& what) const
    {
        in_.fail(element_->name + " " + std::to_string(index_) + ": " + what);
    }

private:
    TextReader::What what() const { return {element_->value_what, index_}; }

    TextReader in_;
    const Element* element_ = nullptr;
    uint64_t index_ = 0;
};

// ---------------------------------------------------------------------------------- body --

template <class Source> void skip_property(Source& src, const Property& p)
{
    if (p.list)
        src.skip_list(p.count_type, p.type);
    else
        src.skip(p.type);
}

template <class Source> void read_vertices(Source& src, const Layout& l, TriangleMesh& mesh)
{
    const auto& e = *l.vertex;
    const bool normals = l.nx >= 0 && l.ny >= 0 && l.nz >= 0;
    mesh.positions.resize(e.count);
    if (normals) mesh.normals.resize(e.count);
    // Property index feeding each of x, y, z, nx, ny, nz (-1: none; normals only when complete).
    const int slots[6] = {l.x, l.y, l.z, normals ? l.nx : -1, normals ? l.ny : -1, normals ? l.nz : -1};
    for (uint64_t v = 0; v < e.count; ++v) {
        src.begin(e, v);
        for (size_t i = 0; i < e.properties.size(); ++i) {
            const auto& p = e.properties[i];
            if (p.list) {
                skip_property(src, p);
                continue;
            }
            const float value = static_cast<float>(src.scalar(p.type));
            for (int s = 0; s < 6; ++s)
                if (slots[s] == int(i)) (s < 3 ? mesh.positions[v][s] : mesh.normals[v][s - 3]) = value;
        }
    }
}

template <class Source>
void read_polygon(Source& src, const Property& p, uint64_t vertex_count, std::vector<uint32_t>& polygon)
{
    const int64_t n = src.integer(p.count_type);
    if (n < 3) src.fail("polygon has " + std::to_string(n) + " vertices (at least 3 needed)");
    polygon.clear();
    for (int64_t k = 0; k < n; ++k) {
        const int64_t index = src.integer(p.type);
        if (index < 0 || uint64_t(index) >= vertex_count)
            src.fail("vertex index " + std::to_string(index) + " out of range for " + std::to_string(vertex_count) +
                     " vertices");
        polygon.push_back(static_cast<uint32_t>(index));
    }
}

template <class Source> void read_faces(Source& src, const Layout& l, TriangleMesh& mesh)
{
    const auto& e = *l.face;
    mesh.indices.reserve(e.count * 3);
    std::vector<uint32_t> polygon;
    for (uint64_t f = 0; f < e.count; ++f) {
        src.begin(e, f);
        for (size_t i = 0; i < e.properties.size(); ++i) {
            if (int(i) != l.indices) {
                skip_property(src, e.properties[i]);
                continue;
            }
            read_polygon(src, e.properties[i], l.vertex->count, polygon);
            append_fan(polygon, mesh.indices);
        }
    }
}

template <class Source> void read_body(Source& src, const Header& h, const Layout& l, TriangleMesh& mesh)
{
    for (const auto& e : h.elements) {
        if (&e == l.vertex) {
            read_vertices(src, l, mesh);
        } else if (&e == l.face) {
            read_faces(src, l, mesh);
        } else {
            for (uint64_t i = 0; i < e.count; ++i) {
                src.begin(e, i);
                for (const auto& p : e.properties) skip_property(src, p);
            }
        }
    }
}

}  // namespace

TriangleMesh read_ply(const std::string& name, std::string_view bytes)
{
    if (bytes.empty()) fail(name, "file is empty");
    const Header header = HeaderParser(name, bytes).parse();
    const Layout layout = find_layout(name, header);
    const auto body = bytes.substr(header.body_offset);
    check_counts(name, header, layout, body.size());

    TriangleMesh mesh;
    mesh.name = name;
    if (header.format == Format::Ascii) {
        AsciiSource src(name, body, header.body_line);
        read_body(src, header, layout, mesh);
    } else {
        BinarySource src(name, body, header.body_offset, header.format == Format::BinaryBigEndian);
        read_body(src, header, layout, mesh);
    }
    return mesh;
}

}  // namespace jade::io
