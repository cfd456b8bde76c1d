// `rheodda plot` of a run's bolts (plot_bolts.cpp).
#pragma once

#include <string>

namespace rheodda::scene {

/// The axial force of every bolt of OUT_DIR/bolts.csv against time into
/// OUT_DIR/plots/bolts.<format> (script and data beside it); returns the picture.
std::string plot_bolts(const std::string& out_dir, const std::string& format, const std::string& title,
                       const std::string& time_unit, const std::string& force_unit, const std::string& length_unit);

}  // namespace rheodda::scene
