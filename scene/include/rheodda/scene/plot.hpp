// `rheodda plot`: pictures of a run's outputs drawn by gnuplot (an external
// program, called with a generated script): the blocks at chosen times (initial
// outline dashed, deformed outline solid, displacements magnified when they are
// too small to see) and the history curves of history.csv.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rheodda/scene/scene.hpp"

namespace rheodda::scene {

/// Runs `gnuplot SCRIPT`; throws std::runtime_error if it cannot start or fails
/// (every picture of the program is drawn this way: plot, study, forecast).
void run_gnuplot(const std::string& script);

/// Text inside a gnuplot single-quoted string ('' stands for ').
std::string gnuplot_text(const std::string& s);

/// `s` as a gnuplot double-quoted string broken at spaces into lines of at most
/// `width` characters (a word longer than that keeps its own line), for a
/// picture's title: a study case's title lists every setting it changes.
std::string gnuplot_wrapped(const std::string& s, std::size_t width);

/// The look of curve `i` of a picture with many (a study's cases, the laws of a fit):
/// ten colours that stay apart (Tableau 10), solid for the first ten curves, then the
/// same colours dashed, dash-dotted and dotted, so that 40 curves are told apart before
/// any repeats (gnuplot's own line types repeat after 8); `point` likewise for points.
struct CurveStyle {
  std::string colour;  ///< "#rrggbb"
  int dash = 1;        ///< gnuplot dash type: 1 solid, 2 dashed, 4 dash-dotted, 3 dotted
  int point = 7;       ///< gnuplot point type: 7 circle, 5 square, 9 triangle, 13 diamond (filled)
  /// "lc rgb '#rrggbb' dt N" for a line.
  std::string line() const;
};
CurveStyle curve_style(std::size_t i);

/// The unit of a column of history.csv (docs/reference/outputs.md) as an axis label
/// shows it in brackets, in the run's unit labels: "m" for a displacement, "N/m
/// thickness" for a force (per unit thickness), "N*m/m thickness" for an energy, "d" for
/// a time, "-" for a count or a ratio; "" for a column it does not know.
std::string history_column_unit(const std::string& column, const std::string& length, const std::string& force,
                                const std::string& time);

struct PlotOptions {
  std::string out_dir;         ///< a run's output directory
  std::vector<double> times;   ///< draw the frames nearest these times [time]; empty: first, middle, last
  std::string format = "png";  ///< "png" or "svg"
  double scale = 0.0;          ///< displacement magnification; 0: automatic (1 unless displacements are tiny)
  /// The contacts.csv column the contacts pictures colour the contacts by (one of
  /// contact_colour_columns()).
  std::string contact_column = "creep_displacement";
  /// The time window [time]: history.png spans it, and without `times` the frames drawn
  /// are the first, middle and last within it. Unset: the run's start, its end.
  std::optional<double> from, to;
  /// Receives each warning, e.g. a requested time after the run's last frame (the last frame
  /// is drawn instead); `rheodda plot` prints them. Empty: warnings are not reported.
  std::function<void(const std::string&)> warn;
};

/// The columns of contacts.csv a contacts picture can colour the contacts by (its numeric
/// columns), and `mobilised_friction` = |shear_force| / shear_strength.
const std::vector<std::string>& contact_colour_columns();

/// The blocks of a scene, each edge coloured by its joint set (a rock mass's region
/// boundary in grey), with each set's joint length in the key, into `picture`
/// (gnuplot script and data beside it); returns `picture`. Throws std::runtime_error if gnuplot fails.
std::string plot_scene(const SceneDescription& s, const std::string& picture, const std::string& format);

/// `options.out_dir` may also be a scene file: then plot_scene() into <scene without extension>-blocks.<format>.
/// Writes OUTDIR/plots/blocks_<frame>.<format>, with contacts.csv
/// OUTDIR/plots/contacts_<frame>.<format> and strength_<frame>.<format> (plot_contacts.hpp),
/// and OUTDIR/plots/history.<format> (and the gnuplot scripts and data next to them);
/// returns the pictures' paths.
/// Throws std::invalid_argument for a directory that holds no run, std::runtime_error if gnuplot fails.
std::vector<std::string> plot_run(const PlotOptions& options);

}  // namespace rheodda::scene
