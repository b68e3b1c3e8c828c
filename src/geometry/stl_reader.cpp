// SPDX-License-Identifier: MIT
#include "geometry/stl_reader.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <sstream>
#include <string>

#include "core/error.h"

namespace sabo::geometry {

namespace {

// Adds triangles to one part, welding corners with equal coordinates.
class PartBuilder {
  public:
    PartBuilder(TriangleMesh& mesh, std::string name) : mesh_(mesh) {
        part_ = static_cast<std::uint16_t>(mesh.part_names.size());
        mesh.part_names.push_back(std::move(name));
    }
    void triangle(const std::array<Vec3, 3>& c) {
        std::array<std::uint32_t, 3> t{};
        for (std::size_t k = 0; k < 3; ++k) t[k] = vertex(c[k]);
        mesh_.triangles.push_back(t);
        mesh_.part.push_back(part_);
    }

  private:
    std::uint32_t vertex(const Vec3& p) {
        const auto [it, fresh] =
            index_.try_emplace({p.x, p.y, p.z}, static_cast<std::uint32_t>(mesh_.vertices.size()));
        if (fresh) mesh_.vertices.push_back(p);
        return it->second;
    }
    TriangleMesh& mesh_;
    std::uint16_t part_ = 0;
    std::map<std::array<double, 3>, std::uint32_t> index_;
};

TriangleMesh read_binary(const std::string& bytes, const std::filesystem::path& file) {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, sizeof(count));
    if (bytes.size() != 84 + 50 * static_cast<std::uint64_t>(count))
        throw InputError(
            fmt::format("{}: not an STL file: a binary STL of {} triangles has {} bytes, this one {}",
                        file.string(), count, 84 + 50 * static_cast<std::uint64_t>(count), bytes.size()));
    TriangleMesh mesh;
    PartBuilder part(mesh, file.stem().string());
    for (std::uint32_t t = 0; t < count; ++t) {
        const char* at =
            bytes.data() + 84 + 50 * static_cast<std::size_t>(t) + 12;  // (the normal is derived)
        std::array<Vec3, 3> c{};
        for (std::size_t k = 0; k < 3; ++k) {
            std::array<float, 3> v{};
            std::memcpy(v.data(), at + 12 * k, sizeof(v));
            c[k] = {v[0], v[1], v[2]};
        }
        part.triangle(c);
    }
    return mesh;
}

TriangleMesh read_ascii(const std::string& text, const std::filesystem::path& file) {
    TriangleMesh mesh;
    std::istringstream in(text);
    std::string line;
    int number = 0;
    std::optional<PartBuilder> part;
    std::array<Vec3, 3> corners{};
    int vertices = 0;
    const auto fail = [&](const std::string& why) {
        throw InputError(fmt::format("{}:{}: {}", file.string(), number, why));
    };
    while (std::getline(in, line)) {
        ++number;
        std::istringstream words(line);
        std::string word;
        if (!(words >> word)) continue;
        if (word == "solid") {
            if (part) fail("'solid' inside another solid (a missing 'endsolid')");
            std::string name;
            std::getline(words >> std::ws, name);
            while (!name.empty() && (name.back() == '\r' || name.back() == ' ')) name.pop_back();
            part.emplace(mesh, name.empty() ? fmt::format("part {}", mesh.parts()) : name);
        } else if (word == "endsolid") {
            if (!part) fail("'endsolid' without 'solid'");
            part.reset();
        } else if (word == "outer" || word == "facet") {
            if (!part) fail(fmt::format("'{}' outside a solid", word));
            if (word == "outer") vertices = 0;
        } else if (word == "vertex") {
            if (!part) fail("'vertex' outside a solid");
            if (vertices >= 3) fail("a facet with more than 3 vertices");
            Vec3 p;
            if (!(words >> p.x >> p.y >> p.z) || !std::isfinite(p.x) || !std::isfinite(p.y) ||
                !std::isfinite(p.z))
                fail("a vertex needs three finite numbers");
            corners[static_cast<std::size_t>(vertices++)] = p;
        } else if (word == "endloop") {
            if (vertices != 3) fail(fmt::format("a facet with {} vertices (3 expected)", vertices));
            part->triangle(corners);
        } else if (word != "endfacet") {
            fail(fmt::format(
                "unexpected '{}' (solid, facet, outer loop, vertex, endloop, endfacet, endsolid)", word));
        }
    }
    if (part) fail("the last solid has no 'endsolid'");
    if (mesh.parts() == 0) throw InputError(fmt::format("{}: no solid in the file", file.string()));
    return mesh;
}

}  // namespace

TriangleMesh read_stl(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in)
        throw InputError(fmt::format("{}: cannot be read (no such file, or no permission)", file.string()));
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // a binary file's header may start with "solid" too: its size tells
    bool binary = bytes.size() >= 84;
    if (binary) {
        std::uint32_t count = 0;
        std::memcpy(&count, bytes.data() + 80, sizeof(count));
        binary = bytes.size() == 84 + 50 * static_cast<std::uint64_t>(count) || bytes.rfind("solid", 0) != 0;
    }
    TriangleMesh mesh = binary ? read_binary(bytes, file) : read_ascii(bytes, file);
    if (mesh.triangles.empty()) throw InputError(fmt::format("{}: no triangles", file.string()));
    return mesh;
}

}  // namespace sabo::geometry
