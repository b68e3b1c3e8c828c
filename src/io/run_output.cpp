// SPDX-License-Identifier: MIT
#include "io/run_output.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <span>
#include <stdexcept>

#include "core/error.h"
#include "io/atomic_file.h"

namespace sabo::io {

CsvSeries::CsvSeries(std::filesystem::path path, const std::vector<std::string>& columns)
    : path_(std::move(path)),
      header_(fmt::format("{}\n", fmt::join(columns, ","))),
      columns_(columns.size()) {}

void CsvSeries::close() {
    if (file_ != nullptr) std::fclose(file_);
    file_ = nullptr;
}

void CsvSeries::open() {
    const std::uint64_t keep = keep_;
    rows_ = 0;
    std::string text = header_;
    if (keep > 0) {
        std::ifstream in(path_);
        std::string line;
        if (!std::getline(in, line) || line + '\n' != header_)
            throw InputError(
                fmt::format("{}: not the series this run writes (cannot resume it)", path_.string()));
        for (; rows_ < keep; ++rows_) {
            if (!std::getline(in, line))
                throw InputError(fmt::format("{}: {} rows, the checkpoint was taken after {}", path_.string(),
                                             rows_, keep));
            text += line + '\n';
        }
    }
    write_text_atomically(path_, text);  // the header, and the rows kept from before the checkpoint
    file_ = std::fopen(path_.string().c_str(), "a");
    if (file_ == nullptr)
        throw RunError(fmt::format("cannot write {}: {}", path_.string(), std::strerror(errno)));
}

CsvSeries::~CsvSeries() {
    close();
}

void CsvSeries::row(const std::vector<double>& values) {
    if (values.size() != columns_) throw std::logic_error("CSV row has the wrong number of columns");
    if (path_.empty()) {
        ++rows_;
        return;
    }
    if (file_ == nullptr) open();
    fmt::print(file_, "{:.9g}\n", fmt::join(values, ","));
    if (std::fflush(file_) != 0)
        throw RunError(fmt::format("writing {} failed: {}", path_.string(), std::strerror(errno)));
    ++rows_;
}

FrameWriter::FrameWriter(std::filesystem::path dir)
    : dir_(std::move(dir)), particles_(dir_ / "particles.pvd"), barrier_(dir_ / "barrier_spheres.pvd") {
    std::filesystem::create_directories(dir_ / "frames");
}

void FrameWriter::write(double time, const dem::Particles& p, std::span<const std::uint32_t> ids) {
    const auto nm = p.n_mobile;
    const std::string name = fmt::format("frames/particles_{:05d}.vtp", index_);
    PolyDataWriter w(std::span(p.x.data(), nm));
    w.scalar("radius_m", std::span(p.r.data(), nm));
    w.vector("velocity_m_s", std::span(p.v.data(), nm));
    w.vector("angular_velocity_rad_s", std::span(p.w.data(), nm));
    w.vector("contact_force_N", std::span(p.f.data(), nm));
    // grains are renumbered by the spatial sorting (dem.reorder_every_builds): id is the grain's
    // index in the initial release, stable over the run
    ids_.assign(ids.begin(), ids.begin() + static_cast<std::ptrdiff_t>(nm));
    w.scalar("id", ids_);
    w.write(dir_ / name);
    particles_.add(time, name);
    if (p.n_fixed() > 0) {
        const std::string bname = fmt::format("frames/barrier_spheres_{:05d}.vtp", index_);
        PolyDataWriter b(std::span(p.x.data() + nm, p.n_fixed()));
        b.scalar("radius_m", std::span(p.r.data() + nm, p.n_fixed()));
        b.vector("force_N", std::span(p.f.data() + nm, p.n_fixed()));
        b.write(dir_ / bname);
        barrier_.add(time, bname);
    }
    ++index_;
}

}  // namespace sabo::io
