// SPDX-License-Identifier: MIT
// STL files, ASCII or binary (docs/geometry.md): each ASCII `solid` becomes a part of the mesh, named as the
// solid is (or "part N"); a binary file is one part named after the file. Corners at the same coordinates
// become one vertex within a part. Errors name the file and the line or triangle.
#pragma once
#include <filesystem>

#include "geometry/triangle_mesh.h"

namespace sabo::geometry {

[[nodiscard]] TriangleMesh read_stl(const std::filesystem::path& file);

}  // namespace sabo::geometry
