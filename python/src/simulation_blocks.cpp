// rheodda.Simulation's blocks (simulation.hpp): each block's state read one
// block at a time or as arrays (Blocks' views), the blocks fixed, freed and
// removed and loads added and removed between steps (Engine::edit), and the
// contacts and bolts as arrays.
#include <rheodda/contact/strength.hpp>
#include <rheodda/core/bolt.hpp>
#include <rheodda/scene/edits.hpp>

#include <algorithm>
#include <cmath>

#include "simulation.hpp"

namespace rheodda::python {
namespace {

/// The width of a block quantity's row (1: a scalar per block), or 0 for an unknown name.
int quantity_width(const std::string& q) {
  if (q == "position") return 2;
  if (q == "velocity") return 6;
  if (q == "strain" || q == "stress") return 3;
  if (q == "rotation" || q == "area" || q == "mass") return 1;
  return 0;
}

json point_json(const core::Vec2& p) { return {hex(p.x()), hex(p.y())}; }

/// Columns by name as a dict of read-only numpy arrays, in the given order (docs/guide/python.md,
/// "numpy conventions").
py::dict read_only_columns(std::initializer_list<std::pair<const char*, py::array>> columns) {
  py::dict d;
  for (const auto& [name, a] : columns) d[name] = read_only(a);
  return d;
}

}  // namespace

void Simulation::check_block(int b) const {
  if (b < 0 || b >= eng().block_count())
    throw InputError(fmt::format("block {} does not exist; the scene has {} blocks", b, eng().block_count()));
}

/// Block b's value of `quantity` into `out` (quantity_width(quantity) numbers).
///   position  the centroid (x, y) [length]
///   rotation  the angle of R in the polar decomposition F = R U of the block's affine map
///             F = map_A (x = F x0 + b): R^T F symmetric gives tan(theta) = (F21 - F12) / (F11 + F22)
///             (with R = [[c, -s], [s, c]], (R^T F)12 = (R^T F)21 <=> s (F11 + F22) = c (F21 - F12);
///             atan2 picks the root with U positive definite) [rad], counter-clockwise > 0
///   strain    the Green-Lagrange strain E = (F^T F - I) / 2 (Holzapfel 2000, Nonlinear Solid
///             Mechanics, sec. 2.5) as (E_xx, E_yy, gamma_xy = 2 E_xy) [-]: zero for a rigid motion
///   velocity  (u0, v0, r0, ex, ey, gxy) rates [length/time, 1/time]
///   stress    (sigma_x, sigma_y, tau_xy) [stress], tension > 0
///   area      the current area S [length^2]
///   mass      density x S, per unit thickness, the mass of the engine's inertia term [mass]
static void block_quantity(const core::Engine& e, int b, const std::string& q, double* out) {
  const core::BlockState& st = e.block(b);
  const core::Mat2& F = st.map_A;
  if (q == "position") {
    out[0] = st.centroid.x();
    out[1] = st.centroid.y();
  } else if (q == "rotation") {
    out[0] = std::atan2(F(1, 0) - F(0, 1), F(0, 0) + F(1, 1));
  } else if (q == "strain") {
    const core::Mat2 E = 0.5 * (F.transpose() * F - core::Mat2::Identity());
    out[0] = E(0, 0);
    out[1] = E(1, 1);
    out[2] = 2.0 * E(0, 1);
  } else if (q == "velocity") {
    for (int i = 0; i < 6; ++i) out[i] = st.velocity[i];
  } else if (q == "stress") {
    for (int i = 0; i < 3; ++i) out[i] = st.stress[i];
  } else if (q == "area") {
    out[0] = e.area(b);
  } else if (q == "mass") {
    out[0] = e.model().materials[static_cast<std::size_t>(st.material)].density * e.area(b);
  }
}

static bool block_fixed(const core::Engine& e, int b) {
  for (const auto& f : e.model().fixed_points)
    if (f.block == b) return true;
  return false;
}

py::array Simulation::block_column(const std::string& q) const {
  const core::Engine& e = eng();
  const int n = e.block_count();
  if (q == "fixed" || q == "removed") {
    py::array_t<bool> a(n);
    for (int b = 0; b < n; ++b) a.mutable_at(b) = q == "fixed" ? block_fixed(e, b) : e.removed(b);
    return read_only(a);
  }
  const int w = quantity_width(q);
  if (w == 0) throw InputError(fmt::format("blocks: no quantity '{}'", q));
  py::array_t<double> a = w == 1 ? py::array_t<double>(n) : py::array_t<double>({n, w});
  double* p = a.mutable_data();
  for (int b = 0; b < n; ++b) block_quantity(e, b, q, p + static_cast<std::ptrdiff_t>(b) * w);
  return read_only(a);
}

py::object Simulation::block_value(int b, const std::string& q) const {
  check_block(b);
  if (q == "fixed") return py::bool_(block_fixed(eng(), b));
  if (q == "removed") return py::bool_(eng().removed(b));
  const int w = quantity_width(q);
  if (w == 0) throw InputError(fmt::format("Block: no quantity '{}'", q));
  py::array_t<double> a(w);
  block_quantity(eng(), b, q, a.mutable_data());
  if (w == 1) return py::float_(a.at(0));
  return read_only(a);
}

py::array_t<double> Simulation::vertices(int b) const {
  check_block(b);
  const auto v = eng().vertices(b);
  py::array_t<double> a({static_cast<py::ssize_t>(v.size()), py::ssize_t{2}});
  auto r = a.mutable_unchecked<2>();
  for (std::size_t k = 0; k < v.size(); ++k) {
    r(k, 0) = v[k].x();
    r(k, 1) = v[k].y();
  }
  return read_only(a);
}

py::array_t<double> Simulation::point_displacement(int b, double x, double y) const {
  check_block(b);
  const core::Vec2 d = eng().point_displacement(b, {x, y});
  py::array_t<double> a(2);
  a.mutable_at(0) = d.x();
  a.mutable_at(1) = d.y();
  return read_only(a);
}

// --- changes through Engine::edit -------------------------------------------

core::EditReport Simulation::apply_edit(const core::ModelEdit& e, const std::string& what) {
  if (failed_) throw RunFailure("the simulation failed earlier (" + failure_ + "); build a new one");
  core::EditReport rep;
  try {
    rep = eng().edit(e);
  } catch (const core::ModelError& err) {
    throw core::ModelError(scene::edit_key(err), fmt::format("{}: {}", what, err.message()));  // edits.hpp
  }
  // The edit with its points as material points (EditReport::replay), for restore().
  const core::ModelEdit& r = rep.replay;
  json c = {{"kind", "edit"},
            {"remove_fixed_points", r.remove_fixed_points},
            {"remove_point_loads", r.remove_point_loads},
            {"remove_blocks", r.remove_blocks}};
  json fixed = json::array();
  for (const auto& f : r.add_fixed_points) {
    json j = {{"block", f.block}, {"point", point_json(f.point)}, {"material_point", point_json(f.material())},
              {"hold_x", f.hold_x}, {"hold_y", f.hold_y}};
    if (f.hold_rotation) {  // the rotation held [rad], as the edit resolved it
      j["hold_rotation"] = true;
      j["held_rotation"] = hex(f.held_rotation.value_or(0.0));
    }
    fixed.push_back(std::move(j));
  }
  json loads = json::array();
  for (const auto& l : r.add_point_loads) {
    json h = json::array();
    for (const auto& s : l.history) h.push_back({hex(s.time), hex(s.force.x()), hex(s.force.y())});
    loads.push_back({{"block", l.block}, {"point", point_json(l.point)}, {"history", h}});
  }
  c["add_fixed_points"] = fixed;
  c["add_point_loads"] = loads;
  changes_.push_back(std::move(c));
  // The loads' ids follow the engine's list: explicit removals, then those on removed blocks, then the added.
  auto erase = [&](std::vector<int> which) {
    std::sort(which.rbegin(), which.rend());
    for (int i : which) load_ids_.erase(load_ids_.begin() + i);
  };
  erase(e.remove_point_loads);
  erase(rep.point_loads_removed);
  for (std::size_t k = 0; k < e.add_point_loads.size(); ++k) load_ids_.push_back(next_load_id_++);
  return rep;
}

void Simulation::fix(int b, const std::vector<std::string>& dofs) {
  check_block(b);
  const std::string what = fmt::format("Block.fix of block '{}' ({})", scene_.blocks[b].name, b);
  bool x = false, y = false, rotation = false;
  for (const std::string& d : dofs) {
    bool& held = d == "x" ? x : d == "y" ? y : rotation;
    if (d != "x" && d != "y" && d != "rotation")
      throw InputError(fmt::format("{}: dofs: unknown '{}'; give some of 'x', 'y', 'rotation'", what, d));
    if (held) throw InputError(fmt::format("{}: dofs: '{}' given twice", what, d));
    held = true;
  }
  if (!x && !y && !rotation)
    throw InputError(fmt::format("{}: dofs: an empty list holds nothing; give some of 'x', 'y', 'rotation'", what));
  // All three: a fixed point at every vertex (as a scene's `fixed: true`), the block held
  // whole. Else one at the centroid, held in the directions given and, with 'rotation', in
  // rotation (a rotational spring p J/S on the block's mean rotation, held at the one it
  // has now, as a scene's `hold: rotation`; core/src/block_terms.hpp, RotationHold);
  // without it the block turns freely about the point.
  core::ModelEdit e;
  auto add = [&](const core::Vec2& p, bool turn) {
    core::FixedPoint fp{b, p};
    fp.hold_x = x;
    fp.hold_y = y;
    fp.hold_rotation = turn;
    e.add_fixed_points.push_back(fp);
  };
  if (x && y && rotation)
    for (const core::Vec2& v : eng().vertices(b)) add(v, false);
  else
    add(eng().centroid(b), rotation);
  apply_edit(e, what);
}

void Simulation::set_velocity(int b, const std::vector<double>& v) {
  check_block(b);
  const std::string what = fmt::format("Block.velocity of block '{}' ({})", scene_.blocks[b].name, b);
  if (v.size() != 3 && v.size() != 6)
    throw InputError(fmt::format("{}: expected (vx, vy, omega) or (vx, vy, omega, ex, ey, gxy), got {} numbers",
                                 what, v.size()));
  core::Vec6 velocity = core::Vec6::Zero();
  for (std::size_t i = 0; i < v.size(); ++i) velocity[static_cast<Eigen::Index>(i)] = v[i];
  core::ModelEdit e;
  e.set_velocities.emplace_back(b, velocity);
  apply_edit(e, what);
}

void Simulation::free(int b) {
  check_block(b);
  core::ModelEdit e;
  const auto& fixed = eng().model().fixed_points;
  for (std::size_t k = 0; k < fixed.size(); ++k)
    if (fixed[k].block == b) e.remove_fixed_points.push_back(static_cast<int>(k));
  const std::string what = fmt::format("Block.free of block '{}' ({})", scene_.blocks[b].name, b);
  if (e.remove_fixed_points.empty()) throw InputError(what + ": the block has no fixed point");
  apply_edit(e, what);
}

void Simulation::remove(int b) {
  check_block(b);
  core::ModelEdit e;
  e.remove_blocks.push_back(b);
  apply_edit(e, fmt::format("Block.remove of block '{}' ({})", scene_.blocks[b].name, b));
}

long Simulation::add_load(int b, double x, double y, const std::vector<std::array<double, 3>>& samples) {
  check_block(b);
  core::PointLoad l;
  l.block = b;
  l.point = {x, y};
  // The samples' times count from now, as a stage's loads' (docs/reference/stages.md).
  for (const auto& s : samples) l.history.push_back({eng().time() + s[0], {s[1], s[2]}});
  core::ModelEdit e;
  e.add_point_loads.push_back(std::move(l));
  apply_edit(e, fmt::format("Block.add_load on block '{}' ({})", scene_.blocks[b].name, b));
  return load_ids_.back();
}

void Simulation::remove_load(long id) {
  const auto it = std::find(load_ids_.begin(), load_ids_.end(), id);
  if (it == load_ids_.end())
    throw InputError(fmt::format("Load.remove: load {} is not in the model any more (removed, or on a removed block)",
                                 id));
  core::ModelEdit e;
  e.remove_point_loads.push_back(static_cast<int>(it - load_ids_.begin()));
  apply_edit(e, fmt::format("Load.remove of load {}", id));
}

// --- contacts and bolts --------------------------------------------------------

py::dict Simulation::contacts() const {
  const core::Engine& e = eng();
  const auto cs = contacts_->contacts();
  const auto states = contacts_->rheology_states();
  const auto incr = contacts_->creep_increments();
  const auto n = static_cast<py::ssize_t>(cs.size());
  std::vector<long> id, js, vb, vx, eb, ed;
  std::vector<double> x, y, nf, sf, ss, sd, pen, len, trib, creep, dcreep;
  py::array_t<double> q({n, py::ssize_t{laws::kMaxInternal}});
  auto qr = q.mutable_unchecked<2>();
  std::vector<std::string> state_names, kind_names;
  for (py::ssize_t i = 0; i < n; ++i) {
    const contact::Contact& c = cs[i];
    id.push_back(static_cast<long>(c.id));
    js.push_back(c.joint_set);
    state_names.emplace_back(contact::contact_state_name(c.state));
    kind_names.emplace_back(contact::contact_kind_name(c.kind));
    vb.push_back(c.key.vblock);
    vx.push_back(c.key.vertex);
    eb.push_back(c.key.eblock);
    ed.push_back(c.key.edge);
    const core::Vec2 p = e.vertices(c.key.vblock)[c.key.vertex];
    x.push_back(p.x());
    y.push_back(p.y());
    nf.push_back(c.normal_force);
    sf.push_back(c.shear_force);
    ss.push_back(contact::mohr_coulomb_strength(contacts_->joint_sets()[c.joint_set], c.normal_force, c.length, c.intact));
    sd.push_back(c.shear_displacement);
    pen.push_back(c.penetration);
    len.push_back(c.length);
    trib.push_back(c.tributary_length);
    const laws::RheologyState st = c.rheology >= 0 ? states[c.rheology] : laws::RheologyState{};
    creep.push_back(st.creep());
    for (int k = 0; k < laws::kMaxInternal; ++k) qr(i, k) = st.q[k];
    dcreep.push_back(i < static_cast<py::ssize_t>(incr.size()) ? incr[i] : 0.0);
  }
  return read_only_columns({{"id", to_numpy(id)}, {"joint_set", to_numpy(js)}, {"state", str_array(state_names)},
                            {"kind", str_array(kind_names)}, {"vertex_block", to_numpy(vb)}, {"vertex", to_numpy(vx)},
                            {"edge_block", to_numpy(eb)}, {"edge", to_numpy(ed)}, {"x", to_numpy(x)},
                            {"y", to_numpy(y)}, {"normal_force", to_numpy(nf)}, {"shear_force", to_numpy(sf)},
                            {"shear_strength", to_numpy(ss)}, {"shear_displacement", to_numpy(sd)},
                            {"penetration", to_numpy(pen)}, {"length", to_numpy(len)},
                            {"tributary_length", to_numpy(trib)}, {"creep_displacement", to_numpy(creep)},
                            {"creep_increment", to_numpy(dcreep)}, {"q", q}});
}

py::dict Simulation::bolts() const {
  // The columns of bolts.csv (docs/reference/bolts.md) after the last accepted step.
  const auto& bs = eng().bolts();
  std::vector<std::string> name, state;
  std::vector<double> force, length, elongation, plastic, creep, rupture;
  for (std::size_t k = 0; k < bs.size(); ++k) {
    name.push_back(k < scene_.bolts.size() ? scene_.bolts[k].name : std::to_string(k));
    state.emplace_back(core::bolt_mode_name(bs[k].state));
    force.push_back(bs[k].force);
    length.push_back(bs[k].length);
    elongation.push_back(bs[k].elongation);
    plastic.push_back(bs[k].plastic_elongation);
    creep.push_back(bs[k].creep_elongation());
    rupture.push_back(bs[k].rupture_time);
  }
  return read_only_columns({{"name", str_array(name)}, {"state", str_array(state)}, {"force", to_numpy(force)},
                            {"length", to_numpy(length)}, {"elongation", to_numpy(elongation)},
                            {"plastic_elongation", to_numpy(plastic)}, {"creep_elongation", to_numpy(creep)},
                            {"rupture_time", to_numpy(rupture)}});
}

void bind_simulation_blocks(py::class_<Simulation>& c) {
  c.def("_block_column", &Simulation::block_column, py::arg("quantity"))
      .def("_block_value", &Simulation::block_value, py::arg("block"), py::arg("quantity"))
      .def("block_vertices", &Simulation::vertices, py::arg("block"))
      .def("point_displacement", &Simulation::point_displacement, py::arg("block"), py::arg("x"), py::arg("y"))
      .def("_fix", &Simulation::fix, py::arg("block"), py::arg("dofs"))
      .def("_set_velocity", &Simulation::set_velocity, py::arg("block"), py::arg("velocity"))
      .def("_free", &Simulation::free, py::arg("block"))
      .def("_remove", &Simulation::remove, py::arg("block"))
      .def("_add_load", &Simulation::add_load, py::arg("block"), py::arg("x"), py::arg("y"), py::arg("samples"))
      .def("_remove_load", &Simulation::remove_load, py::arg("id"))
      .def_property_readonly("_load_ids", &Simulation::load_ids)
      .def("_contacts", &Simulation::contacts)
      .def("_bolts", &Simulation::bolts);
}

}  // namespace rheodda::python
