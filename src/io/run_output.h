// SPDX-License-Identifier: MIT
// Files a DEM run writes into its output folder (docs/outputs.md): the time-series CSV, particle
// and barrier-sphere frames (.vtp + .pvd), and summary.json.
#pragma once
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "dem/dem_solver.h"
#include "io/vtk_writer.h"

namespace sabo::io {

// Append-only CSV with a header of column names that carry their units. Each row is flushed, so
// an interrupted run keeps everything written so far. The file is made at the first row.
class CsvSeries {
  public:
    // An empty path: the rows are counted, nothing is written (the ranks but the first of a divided run).
    CsvSeries(std::filesystem::path path, const std::vector<std::string>& columns);
    ~CsvSeries();
    CsvSeries(const CsvSeries&) = delete;
    CsvSeries& operator=(const CsvSeries&) = delete;
    void row(const std::vector<double>& values);
    [[nodiscard]] std::uint64_t rows() const { return rows_; }
    // The row count (io/checkpoint.h). Read back, the run continues from a checkpoint taken after that many
    // rows: at the next row the file is cut back to them (rows the interrupted run wrote after the
    // checkpoint are dropped) and goes on from there.
    template <class Archive>
    void transfer(Archive& a) {
        std::uint64_t rows = rows_;
        a(rows);
        if constexpr (Archive::reading) {
            close();
            rows_ = keep_ = rows;
        }
    }

  private:
    // Writes the header and the first keep_ rows of the file as it is, and opens it for the next rows.
    void open();
    void close();

    std::filesystem::path path_;
    std::string header_;
    std::FILE* file_ = nullptr;
    std::size_t columns_ = 0;
    std::uint64_t rows_ = 0;
    std::uint64_t keep_ = 0;  // rows of the file that open() keeps
};

// Particle frames: particles_NNNNN.vtp (mobile spheres) and, when the barrier is made of fixed
// spheres, barrier_NNNNN.vtp with the force each sphere received; one .pvd per series.
class FrameWriter {
  public:
    explicit FrameWriter(std::filesystem::path dir);
    // The grains at `time` (synchronous velocities; `ids`: each mobile grain's index in the release).
    void write(double time, const dem::Particles& p, std::span<const std::uint32_t> ids);
    // the frames written so far (io/checkpoint.h)
    template <class Archive>
    void transfer(Archive& a) {
        a(particles_, barrier_, index_);
    }

  private:
    std::filesystem::path dir_;
    PvdSeries particles_, barrier_;
    std::vector<double> ids_;
    int index_ = 0;
};

}  // namespace sabo::io
