// SPDX-License-Identifier: MIT
#include "io/vtk_writer.h"

#include <fmt/format.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/atomic_file.h"

namespace sabo::io {

namespace {

void put_block(std::ostream& os, const void* data, std::uint64_t bytes) {
    os.write(reinterpret_cast<const char*>(&bytes), sizeof(bytes));
    os.write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
}

// An array as VTK's zlib compressor stores it in appended data: the UInt64 header [blocks, block size, size
// of the last partial block (0: none), each block's compressed size], then the blocks. The blocks are
// compressed on all threads, each on its own: the bytes do not depend on the thread count. Lattice frames
// are mostly runs of equal values (empty cells, full cells), which zlib's fastest level shrinks ~10x.
std::string zlib_blocks(const void* data, std::uint64_t bytes) {
    constexpr std::uint64_t block = 1 << 18;
    const std::uint64_t count = (bytes + block - 1) / block;
    std::vector<std::string> packed(count);
    const auto* in = static_cast<const unsigned char*>(data);
    bool failed = false;
#pragma omp parallel for schedule(dynamic, 1) reduction(|| : failed)
    for (std::int64_t b = 0; b < static_cast<std::int64_t>(count); ++b) {
        const auto k = static_cast<std::uint64_t>(b);
        const uLong size = static_cast<uLong>(std::min(block, bytes - k * block));
        uLongf out = compressBound(size);
        packed[k].resize(out);
        failed = failed || compress2(reinterpret_cast<Bytef*>(packed[k].data()), &out, in + k * block, size,
                                     Z_BEST_SPEED) != Z_OK;
        packed[k].resize(out);
    }
    if (failed) throw std::runtime_error("zlib could not compress a frame's array");
    std::vector<std::uint64_t> header{count, block, bytes % block};
    for (const auto& p : packed) header.push_back(p.size());
    std::string out(reinterpret_cast<const char*>(header.data()), header.size() * sizeof(std::uint64_t));
    for (const auto& p : packed) out += p;
    return out;
}

// PolyData of `points` whose cells are `kind` ("Verts" or "Polys": each cell's point indices in
// `connectivity`, its end there at `offsets`), with Float64 arrays of one value (scalars) or three (vectors)
// per point (`data` = "PointData") or per cell ("CellData").
void write_poly_data(const std::filesystem::path& path, std::span<const Vec3> points, const char* kind,
                     std::span<const std::int64_t> connectivity, std::span<const std::int64_t> offsets,
                     const char* data,
                     std::span<const std::pair<std::string, std::span<const double>>> scalars,
                     std::span<const std::pair<std::string, std::span<const Vec3>>> vectors) {
    std::string xml;
    std::uint64_t offset = 0;
    auto array = [&](const char* type, const std::string& name, int comps, std::uint64_t bytes) {
        xml += fmt::format(
            R"(        <DataArray type="{}" Name="{}" NumberOfComponents="{}" format="appended" offset="{}"/>)"
            "\n",
            type, name, comps, offset);
        offset += sizeof(std::uint64_t) + bytes;
    };
    xml += R"(<?xml version="1.0"?>)"
           "\n";
    xml += R"(<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">)"
           "\n";
    xml += fmt::format("  <PolyData>\n    <Piece NumberOfPoints=\"{}\" NumberOf{}=\"{}\">\n", points.size(),
                       kind, offsets.size());
    xml += "      <Points>\n";
    array("Float64", "points", 3, points.size_bytes());
    xml += fmt::format("      </Points>\n      <{}>\n", kind);
    array("Int64", "connectivity", 1, connectivity.size_bytes());
    array("Int64", "offsets", 1, offsets.size_bytes());
    xml += fmt::format("      </{}>\n      <{}>\n", kind, data);
    for (const auto& [name, v] : scalars) array("Float64", name, 1, v.size_bytes());
    for (const auto& [name, v] : vectors) array("Float64", name, 3, v.size_bytes());
    xml += fmt::format("      </{}>\n    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n   _",
                       data);
    write_atomically(path, [&](std::ostream& os) {
        os << xml;
        put_block(os, points.data(), points.size_bytes());
        put_block(os, connectivity.data(), connectivity.size_bytes());
        put_block(os, offsets.data(), offsets.size_bytes());
        for (const auto& [name, v] : scalars) put_block(os, v.data(), v.size_bytes());
        for (const auto& [name, v] : vectors) put_block(os, v.data(), v.size_bytes());
        os << "\n  </AppendedData>\n</VTKFile>\n";
    });
}

}  // namespace

void PolyDataWriter::write(const std::filesystem::path& path) const {
    // one vertex cell per point
    const std::uint64_t n = points_.size();
    std::vector<std::int64_t> conn(n), offs(n);
    for (std::uint64_t i = 0; i < n; ++i) {
        conn[i] = static_cast<std::int64_t>(i);
        offs[i] = static_cast<std::int64_t>(i + 1);
    }
    write_poly_data(path, points_, "Verts", conn, offs, "PointData", scalars_, vectors_);
}

void SurfaceWriter::write(const std::filesystem::path& path) const {
    write_poly_data(path, points_, "Polys", connectivity_, offsets_, "CellData", scalars_, vectors_);
}

void ImageDataWriter::write(const std::filesystem::path& path) const {
    std::string xml =
        R"(<?xml version="1.0"?>)"
        "\n"
        R"(<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian" header_type="UInt64" )"
        R"(compressor="vtkZLibDataCompressor">)"
        "\n";
    const std::string whole = fmt::format("0 {} 0 {} 0 {}", whole_nx_ < 0 ? n_[0] : whole_nx_, n_[1], n_[2]);
    const std::string extent = fmt::format("{} {} 0 {} 0 {}", x0_, x0_ + n_[0], n_[1], n_[2]);
    xml += fmt::format(
        R"(  <ImageData WholeExtent="{}" Origin="{:.9g} {:.9g} {:.9g}" Spacing="{:.9g} {:.9g} {:.9g}">)"
        "\n    <Piece Extent=\"{}\">\n      <CellData>\n",
        whole, origin_.x, origin_.y, origin_.z, h_, h_, h_, extent);
    std::vector<std::string> packed;
    std::uint64_t offset = 0;
    for (const auto& a : arrays_) {
        packed.push_back(zlib_blocks(a.values.data(), a.values.size() * sizeof(float)));
        xml += fmt::format(
            R"(        <DataArray type="Float32" Name="{}" NumberOfComponents="{}" format="appended" offset="{}"/>)"
            "\n",
            a.name, a.components, offset);
        offset += packed.back().size();
    }
    xml += "      </CellData>\n    </Piece>\n  </ImageData>\n  <AppendedData encoding=\"raw\">\n   _";
    write_atomically(path, [&](std::ostream& os) {
        os << xml;
        for (const auto& p : packed) os.write(p.data(), static_cast<std::streamsize>(p.size()));
        os << "\n  </AppendedData>\n</VTKFile>\n";
    });
}

void ImageDataWriter::write_parallel(const std::filesystem::path& path,
                                     const std::vector<ImageDataWriter::Piece>& pieces) const {
    std::string xml = fmt::format(
        "<?xml version=\"1.0\"?>\n"
        R"(<VTKFile type="PImageData" version="1.0" byte_order="LittleEndian" header_type="UInt64">)"
        "\n"
        R"(  <PImageData WholeExtent="0 {} 0 {} 0 {}" GhostLevel="0" Origin="{:.9g} {:.9g} {:.9g}" )"
        R"(Spacing="{:.9g} {:.9g} {:.9g}">)"
        "\n    <PCellData>\n",
        whole_nx_ < 0 ? n_[0] : whole_nx_, n_[1], n_[2], origin_.x, origin_.y, origin_.z, h_, h_, h_);
    for (const auto& a : arrays_)
        xml += fmt::format(R"(      <PDataArray type="Float32" Name="{}" NumberOfComponents="{}"/>)"
                           "\n",
                           a.name, a.components);
    xml += "    </PCellData>\n";
    for (const Piece& p : pieces)
        xml += fmt::format(R"(    <Piece Extent="{} {} 0 {} 0 {}" Source="{}"/>)"
                           "\n",
                           p.begin, p.end, n_[1], n_[2], p.file);
    xml += "  </PImageData>\n</VTKFile>\n";
    write_text_atomically(path, xml);
}

void PvdSeries::add(double time, const std::string& relative_file) {
    entries_.push_back({time, relative_file});
    write_atomically(path_, [this](std::ostream& os) {
        os << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n  <Collection>\n";
        for (const auto& [t, f] : entries_) {
            os << fmt::format("    <DataSet timestep=\"{:.9g}\" part=\"0\" file=\"{}\"/>\n", t, f);
        }
        os << "  </Collection>\n</VTKFile>\n";
    });
}

}  // namespace sabo::io
