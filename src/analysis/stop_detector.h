// SPDX-License-Identifier: MIT
// Complete stop (docs/analysis.md): the total kinetic energy of the grains stays below a threshold for a
// hold time. Fed at regular samples; reports the time the quiet period began.
#pragma once

namespace sabo::analysis {

class StopDetector {
  public:
    StopDetector(double threshold_J, double hold_s) : threshold_(threshold_J), hold_(hold_s) {}
    // True once the energy has stayed below the threshold for the hold time.
    bool sample(double time, double kinetic_energy) {
        if (kinetic_energy >= threshold_) {
            quiet_since_ = -1.0;
        } else if (quiet_since_ < 0.0) {
            quiet_since_ = time;
        }
        return quiet_since_ >= 0.0 && time - quiet_since_ >= hold_;
    }
    [[nodiscard]] double quiet_since() const { return quiet_since_; }  // −1 while moving
    template <class Archive>
    void transfer(Archive& a) {
        a(quiet_since_);
    }

  private:
    double threshold_, hold_;
    double quiet_since_ = -1.0;
};

}  // namespace sabo::analysis
