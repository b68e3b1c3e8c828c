// SPDX-License-Identifier: MIT
// VTK XML PolyData (.vtp) with raw binary appended data (Float64, UInt64 headers), and the .pvd
// collection that gives ParaView the physical time of each frame. Both written atomically.
#pragma once
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

// A growing .pvd series: add() records (time, file name relative to the .pvd) and rewrites it.
class PvdSeries {
  public:
    explicit PvdSeries(std::filesystem::path path) : path_(std::move(path)) {}
    void add(double time, const std::string& relative_file);

  private:
    std::filesystem::path path_;
    std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace sabo::io
