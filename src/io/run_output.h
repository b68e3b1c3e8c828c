// SPDX-License-Identifier: MIT
// Files a DEM run writes into its output folder (docs/outputs.md): the time-series CSV, particle
// and barrier-sphere frames (.vtp + .pvd), and summary.json.
#pragma once
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "dem/dem_solver.h"
#include "io/vtk_writer.h"

namespace sabo::io {

// Append-only CSV with a header of column names that carry their units. Each row is flushed, so
// an interrupted run keeps everything written so far.
class CsvSeries {
  public:
    // `resume_rows`: the run continues from a checkpoint taken after that many rows; the file keeps them
    // (rows the interrupted run wrote after the checkpoint are dropped) and goes on from there.
    CsvSeries(const std::filesystem::path& path, const std::vector<std::string>& columns,
              std::optional<std::uint64_t> resume_rows = std::nullopt);
    ~CsvSeries();
    CsvSeries(const CsvSeries&) = delete;
    CsvSeries& operator=(const CsvSeries&) = delete;
    void row(const std::vector<double>& values);
    [[nodiscard]] std::uint64_t rows() const { return rows_; }

  private:
    std::FILE* file_ = nullptr;
    std::size_t columns_ = 0;
    std::uint64_t rows_ = 0;
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
