// `rheodda plot` of a run's contacts (plot_contacts.cpp): where creep and slip act.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "rheodda/scene/output.hpp"

namespace rheodda::scene {

/// One drawn frame: its number in blocks.pvd, its time and its blocks.
struct ContactFrame {
  std::size_t number = 0;
  double time = 0.0;                        ///< [time]
  const std::vector<FrameBlock>* blocks = nullptr;
};

/// The run's units as summary.json gives them.
struct PlotUnits {
  std::string length, force, time, stress;
};

/// For each frame, from OUT_DIR/contacts.csv:
/// - plots/contacts_NNNNNN.<format>: the blocks (current outline) with their contacts
///   coloured by state (locked, sliding, open), and below by `column` (its magnitude for
///   the columns signed along the contact edge);
/// - plots/strength_NNNNNN.<format>: per joint set with closed contacts, each contact's
///   shear stress |F_s| / l_t against its normal stress F_n / l_t, with its Mohr-Coulomb
///   strength (docs/reference/contacts.md) at the same normal stress: the mobilised friction.
/// Returns the pictures written. Throws std::invalid_argument for a column contacts.csv
/// does not have (naming those it has), std::runtime_error if gnuplot fails.
std::vector<std::string> plot_contacts(const std::string& out_dir, const std::string& format, const std::string& title,
                                       const PlotUnits& units, const std::vector<ContactFrame>& frames,
                                       const std::string& column);

}  // namespace rheodda::scene
