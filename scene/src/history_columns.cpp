// The declarations of history.csv's columns (history_columns.hpp), in the order of a row;
// the energy balance's names are kHistoryEnergyColumns (output.hpp), whose values
// history_energy_values gives in the same order.
#include "rheodda/scene/history_columns.hpp"

#include "rheodda/scene/output.hpp"

namespace rheodda::scene {

namespace {

/// The energy columns [a, b) of kHistoryEnergyColumns.
std::vector<std::string> energy(std::size_t a, std::size_t b) {
  return {kHistoryEnergyColumns.begin() + a, kHistoryEnergyColumns.begin() + b};
}

std::vector<HistoryColumns> declare_history_columns() {
  using P = HistoryPart;
  return {
      {P::step, {"time"}, "time",
         "time at the end of the step"},
      {P::step, {"step"}, "–",
         "accepted steps so far"},
      {P::step, {"dt"}, "time",
         "step size used (0 on the t = 0 row)"},
      {P::step, {"cuts"}, "–",
         "times dt was cut before the step was accepted"},
      {P::step, {"iterations"}, "–",
         "open–close iterations of the accepted step; the cycles of a static step by cycles "
         "(`static_force_ratio`, docs/reference/explicit-step.md)"},
      {P::point, {".u", ".v"}, "length",
         "x and y displacement of each measurement point"},
      {P::point_settled, {".u_after_settling", ".v_after_settling"}, "length",
         "scenes with a settling stage (`analysis.settle`) only, after each point's `.u`, `.v`: its "
         "displacement since the end of the settling stage, `<point>.u` minus its value at the step that "
         "ended the stage. Empty before that step, 0 on its row: the creep and later loading apart from "
         "the settlement under gravity (below)"},
      {P::joint_set, {".contacts"}, "–",
         "closed (sliding or locked) contacts of each joint set with `record: true`"},
      {P::joint_set, {".shear_displacement"}, "length",
         "their mean accumulated shear displacement, signed along the entrance edge (empty when there is "
         "no closed contact)"},
      {P::joint_set, {".shear_force"}, "force",
         "their mean shear force (per unit thickness), same sign convention"},
      {P::joint_set, {".shear_displacement_magnitude"}, "length",
         "their mean \\|accumulated shear displacement\\|: how far the joint's contacts have slipped and "
         "crept, whatever the direction. The signed mean above averages contacts whose entrance edges "
         "point opposite ways (on the seed's slope +0.76 … −0.91 m on the base at 60 d), so it can shrink "
         "while every contact moves; this one cannot cancel"},
      {P::energy, energy(0, 5), "force·length",
         "energy stored now: kinetic, elastic strain of the blocks, fixed-point springs (a held "
         "rotation's spring with them), contact normal and shear springs (per unit thickness, like every "
         "force: J/m in SI)"},
      {P::energy, energy(5, 8), "force·length",
         "since t = 0: work of gravity, of the point loads (and of the water, docs/reference/water.md), "
         "and the energy the contact springs gained between steps without work"},
      {P::energy, energy(8, 16), "force·length",
         "since t = 0: energy taken out by friction, by the creep dashpots, by the time integration, by "
         "the contact dashpots (joint set `restitution`), by the blocks' strain damping (material "
         "`damping_ratio`), by contact springs attached and detached within a step, and by changes "
         "between steps: the kinetic energy of a moving block that fixed points began or stopped holding "
         "(a spin stopped by a held rotation: ½ I ω²), less that of velocities set from Python "
         "(docs/reference/engine.md, \"Fixing and freeing a moving block\")"},
      {P::energy, energy(16, 17), "force·length",
         "since t = 0: change of the stored energy − works + dissipations (> 0: energy gained that no "
         "term explains)"},
      {P::energy, energy(17, 18), "–",
         "\\|energy_residual\\| / (stored energy at t = 0 + Σ over the steps of \\|work_gravity\\| + "
         "\\|work_loads\\|)"},
      {P::energy, energy(18, 19), "–",
         "the row's step: the inertia term's share of its work of gravity and loads, "
         "`integration_inertia` / (\\|work_gravity\\| + \\|work_loads\\|) of that step (0 on the t = 0 "
         "row). In a static analysis above 0.1 the step moved as a mechanism (docs/reference/engine.md, "
         "\"Mechanisms in static analysis\"); in a dynamic one it is the scheme's damping of the kinetic "
         "energy"},
      {P::bolt, {"energy_bolt", "dissipation_bolt"}, "force·length",
         "with bolts only, after `inertia_share`: the energy the bolts store now and, since t = 0, what "
         "they dissipated (docs/reference/bolts.md, \"Energy\")"},
      {P::stage, {"stage"}, "–",
         "scenes with `stages:` only (the last column): the stage in force during the row's step, empty "
         "before the first (docs/reference/stages.md)"},
  };
}

}  // namespace

const std::vector<HistoryColumns>& history_column_specs() {
  static const std::vector<HistoryColumns> specs = declare_history_columns();
  return specs;
}

std::vector<std::string> history_part_columns(HistoryPart p) {
  std::vector<std::string> out;
  for (const HistoryColumns& c : history_column_specs())
    if (c.part == p) out.insert(out.end(), c.names.begin(), c.names.end());
  return out;
}

std::vector<std::string> history_columns_of(const std::vector<std::string>& points, bool settled,
                                            const std::vector<std::string>& recorded_joint_sets, bool bolts,
                                            bool stages) {
  std::vector<std::string> c = history_part_columns(HistoryPart::step);
  for (const std::string& p : points) {
    for (const std::string& f : history_part_columns(HistoryPart::point)) c.push_back(p + f);
    if (settled)
      for (const std::string& f : history_part_columns(HistoryPart::point_settled)) c.push_back(p + f);
  }
  for (const std::string& j : recorded_joint_sets)
    for (const std::string& f : history_part_columns(HistoryPart::joint_set)) c.push_back(j + f);
  for (const std::string& f : history_part_columns(HistoryPart::energy)) c.push_back(f);
  if (bolts)
    for (const std::string& f : history_part_columns(HistoryPart::bolt)) c.push_back(f);
  if (stages)
    for (const std::string& f : history_part_columns(HistoryPart::stage)) c.push_back(f);
  return c;
}

std::string history_table_markdown() {
  std::string out = "| column | unit | meaning |\n|---|---|---|\n";
  for (const HistoryColumns& c : history_column_specs()) {
    const char* owner = c.part == HistoryPart::point || c.part == HistoryPart::point_settled ? "<point>"
                        : c.part == HistoryPart::joint_set                                   ? "<joint_set>"
                                                                                             : "";
    std::string names;
    for (const std::string& n : c.names) names += (names.empty() ? "`" : ", `") + std::string(owner) + n + "`";
    out += "| " + names + " | " + c.unit + " | " + c.meaning + " |\n";
  }
  return out;
}

}  // namespace rheodda::scene
