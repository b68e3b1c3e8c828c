// SPDX-License-Identifier: MIT
// VTK XML PolyData (.vtp) with raw binary appended data (Float64, UInt64 headers), and the .pvd
// collection that gives ParaView the physical time of each frame. Both written atomically.
#pragma once
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/vec3.h"

namespace sabo::io {

class PolyDataWriter {
  public:
    explicit PolyDataWriter(std::span<const Vec3> points) : points_(points) {}
    void scalar(std::string name, std::span<const double> values) {
        scalars_.emplace_back(std::move(name), values);
    }
    void vector(std::string name, std::span<const Vec3> values) {
        vectors_.emplace_back(std::move(name), values);
    }
    void write(const std::filesystem::path& path) const;

  private:
    std::span<const Vec3> points_;
    std::vector<std::pair<std::string, std::span<const double>>> scalars_;
    std::vector<std::pair<std::string, std::span<const Vec3>>> vectors_;
};

// VTK XML PolyData of polygons (a surface): points, each polygon's point indices (`connectivity`, its end in
// it at `offsets`), and cell data (one value per polygon).
class SurfaceWriter {
  public:
    SurfaceWriter(std::span<const Vec3> points, std::span<const std::int64_t> connectivity,
                  std::span<const std::int64_t> offsets)
        : points_(points), connectivity_(connectivity), offsets_(offsets) {}
    void cell_scalar(std::string name, std::span<const double> values) {
        scalars_.emplace_back(std::move(name), values);
    }
    void cell_vector(std::string name, std::span<const Vec3> values) {
        vectors_.emplace_back(std::move(name), values);
    }
    void write(const std::filesystem::path& path) const;

  private:
    std::span<const Vec3> points_;
    std::span<const std::int64_t> connectivity_, offsets_;
    std::vector<std::pair<std::string, std::span<const double>>> scalars_;
    std::vector<std::pair<std::string, std::span<const Vec3>>> vectors_;
};

// VTK XML ImageData (.vti): a regular grid of nx x ny x nz cells (spacing h, the first cell's corner
// at `origin`) with cell data as Float32 (fields for viewing: half the size of Float64), raw binary
// appended. Arrays are copied in, so the caller's buffers may be reused.
class ImageDataWriter {
  public:
    ImageDataWriter(int nx, int ny, int nz, const Vec3& origin, double h)
        : n_{nx, ny, nz}, origin_(origin), h_(h) {}
    void scalar(std::string name, std::vector<float> values) {
        arrays_.push_back({std::move(name), 1, std::move(values)});
    }
    // three components per cell, x y z interleaved
    void vector(std::string name, std::vector<float> xyz) {
        arrays_.push_back({std::move(name), 3, std::move(xyz)});
    }
    void write(const std::filesystem::path& path) const;
    // A piece of a larger image divided along x: these cells are planes [x0, x0 + nx) of `whole_nx` (the
    // origin stays the whole image's).
    void set_piece(int x0, int whole_nx) {
        x0_ = x0;
        whole_nx_ = whole_nx;
    }
    // The .pvti that joins the pieces (file names relative to it, each with its planes [begin, end)) of the
    // whole image this one is a piece of, with this one's arrays.
    struct Piece {
        std::string file;
        int begin = 0, end = 0;
    };
    void write_parallel(const std::filesystem::path& path, const std::vector<Piece>& pieces) const;

  private:
    struct Array {
        std::string name;
        int components;
        std::vector<float> values;
    };
    int n_[3];
    int x0_ = 0, whole_nx_ = -1;  // a piece: its first plane in the whole image, the whole's planes
    Vec3 origin_;
    double h_;
    std::vector<Array> arrays_;
};

// A growing .pvd series: add() records (time, file name relative to the .pvd) and rewrites it.
class PvdSeries {
  public:
    explicit PvdSeries(std::filesystem::path path) : path_(std::move(path)) {}
    void add(double time, const std::string& relative_file);
    // the entries so far (io/checkpoint.h)
    template <class Archive>
    void transfer(Archive& a) {
        a(entries_);
    }

  private:
    struct Entry {
        double time = 0.0;
        std::string file;
        template <class Archive>
        void transfer(Archive& a) {
            a(time, file);
        }
    };
    std::filesystem::path path_;
    std::vector<Entry> entries_;
};

}  // namespace sabo::io
