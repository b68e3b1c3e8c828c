// SPDX-License-Identifier: MIT
// Files a DEM run writes into its output folder (docs/outputs.md): the time-series CSV, particle
// and barrier-sphere frames (.vtp + .pvd), and summary.json.
#pragma once
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "dem/dem_solver.h"
#include "io/vtk_writer.h"

namespace sabo::io {

// Append-only CSV with a header of column names that carry their units. Each row is flushed, so
// an interrupted run keeps everything written so far.
class CsvSeries {
  public:
    CsvSeries(const std::filesystem::path& path, const std::vector<std::string>& columns);
    ~CsvSeries();
    CsvSeries(const CsvSeries&) = delete;
    CsvSeries& operator=(const CsvSeries&) = delete;
    void row(const std::vector<double>& values);

  private:
    std::FILE* file_ = nullptr;
    std::size_t columns_ = 0;
};

// Particle frames: particles_NNNNN.vtp (mobile spheres) and, when the barrier is made of fixed
// spheres, barrier_NNNNN.vtp with the force each sphere received; one .pvd per series.
class FrameWriter {
  public:
    explicit FrameWriter(std::filesystem::path dir);
    void write(const dem::DemSolver& solver);

  private:
    std::filesystem::path dir_;
    PvdSeries particles_, barrier_;
    std::vector<double> ids_;
    int index_ = 0;
};

}  // namespace sabo::io
