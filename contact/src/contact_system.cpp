#include "rheodda/contact/contact_system.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "rheodda/laws/series_law.hpp"

namespace rheodda::contact {

const char* contact_state_name(ContactState s) {
  switch (s) {
    case ContactState::open: return "open";
    case ContactState::sliding: return "sliding";
    case ContactState::locked: return "locked";
  }
  return "?";
}

const char* creep_state_name(CreepState s) {
  switch (s) {
    case CreepState::none: return "none";
    case CreepState::creeping: return "creeping";
    case CreepState::idle: return "idle";
  }
  return "?";
}

namespace {

int wrap(int k, int n) { return (k % n + n) % n; }

/// perp(w) = (-w_y, w_x): perp(w).u = w x u.
Vec2 perp(const Vec2& w) { return {-w.y(), w.x()}; }

Vec2 edge_start(const BlockView& b, int e) { return b.vertices[e]; }
Vec2 edge_end(const BlockView& b, int e) {
  return b.vertices[wrap(e + 1, static_cast<int>(b.vertices.size()))];
}

/// Fraction along a -> b of the projection of p, clamped to [0, 1].
double projection_ratio(const Vec2& a, const Vec2& b, const Vec2& p) {
  const Vec2 ab = b - a;
  return std::clamp(ab.dot(p - a) / ab.squaredNorm(), 0.0, 1.0);
}

/// Fraction along a -> b of the projection of p on the line through a and b,
/// not clamped to [0, 1]: the locking point of a shear spring. A vertex that
/// overhangs its edge's end by a little (a corner contact near the edge end,
/// within the search reach) locks where it is; locking it at the clamped end
/// attaches the spring already stretched by the overhang, energy from nowhere
/// (measured on the stepped slope of bench/scenes/stepped-toppling.yaml: the
/// explosion at dt = 0.1 ms, docs/contacts.md "The locking point").
double line_ratio(const Vec2& a, const Vec2& b, const Vec2& p) {
  const Vec2 ab = b - a;
  return ab.dot(p - a) / ab.squaredNorm();
}

void check_joint_set(const JointSet& js, size_t index) {
  auto bad = [&](const char* key, double v) {
    throw std::invalid_argument("joint set " + std::to_string(index) + " '" + js.name + "': " + key +
                                " = " + std::to_string(v) + " must be >= 0");
  };
  if (!(js.friction_angle >= 0.0) || !(js.friction_angle < 90.0))
    throw std::invalid_argument("joint set " + std::to_string(index) + " '" + js.name +
                                "': friction_angle = " + std::to_string(js.friction_angle) +
                                " must be in [0, 90) deg");
  if (!(js.cohesion >= 0.0)) bad("cohesion", js.cohesion);
  if (!(js.tensile_strength >= 0.0)) bad("tensile_strength", js.tensile_strength);
  if (js.normal_stiffness && !(*js.normal_stiffness > 0.0)) bad("normal_stiffness", *js.normal_stiffness);
  if (js.shear_stiffness && !(*js.shear_stiffness > 0.0)) bad("shear_stiffness", *js.shear_stiffness);
  if (js.restitution && !(*js.restitution >= 0.0 && *js.restitution <= 1.0))
    throw std::invalid_argument("joint set " + std::to_string(index) + " '" + js.name +
                                "': restitution = " + std::to_string(*js.restitution) +
                                " must be in [0, 1]");
  // One elastic shear stiffness per joint: a law's instantaneous spring E1 is it.
  if (js.law && js.law->instantaneous_stiffness() && js.shear_stiffness)
    throw std::invalid_argument("joint set " + std::to_string(index) + " '" + js.name +
                                "': shear_stiffness and the E1 of law '" +
                                std::string(js.law->name()) +
                                "' both set the joint's elastic shear stiffness; give only E1");
}

/// Scheme of a joint set when the settings leave it open: exponential-linear
/// (2nd order) while dt (k + E_i) <= 2 eta_i for every creep element i, where it
/// neither diverges nor rings under the series spring k [stress/length];
/// implicit (monotone at any dt) otherwise (docs/rheology-in-dda.md, "Schemes").
laws::Scheme automatic_scheme(const laws::ContactRheology& law, double k, double dt) {
  const auto* series = dynamic_cast<const laws::SeriesLaw*>(&law);
  if (!series) return laws::Scheme::implicit;
  for (const laws::CreepElement& e : series->elements()) {
    const double E = e.kind == laws::CreepElement::Kind::kelvin ? e.E : 0.0;
    if (dt * (k + E) > 2.0 * e.eta) return laws::Scheme::implicit;
  }
  return laws::Scheme::exponential_linear;
}

/// Reduced mass m_i m_j / (m_i + m_j) of two blocks [mass/length]; a block of
/// infinite (held) or unknown (0) mass leaves the other's; 0 when neither is known.
double reduced_mass(double mi, double mj) {
  const bool ki = mi > 0.0 && std::isfinite(mi), kj = mj > 0.0 && std::isfinite(mj);
  if (ki && kj) return mi * mj / (mi + mj);
  return ki ? mi : kj ? mj : 0.0;
}

}  // namespace

ContactSystem::ContactSystem(std::vector<JointSet> joint_sets, ContactSettings settings)
    : joint_sets_(std::move(joint_sets)), settings_(settings), penalty_(settings.penalty) {
  if (!(settings_.penalty > 0.0))
    throw std::invalid_argument("contact penalty = " + std::to_string(settings_.penalty) +
                                " must be > 0 (Shi: 10-100 x Young's modulus)");
  if (!(settings_.shear_normal_ratio > 0.0))
    throw std::invalid_argument("shear_normal_ratio must be > 0");
  if (joint_sets_.empty()) {
    JointSet js;
    js.name = "default";
    joint_sets_.push_back(js);
  }
  for (size_t k = 0; k < joint_sets_.size(); ++k) check_joint_set(joint_sets_[k], k);
  creep_counters_.assign(joint_sets_.size(), CreepCounters{});
}

void ContactSystem::prepare(std::span<const BlockView> blocks, const Contact& c, Hot& h) const {
  const BlockView& bi = blocks[c.key.vblock];
  const BlockView& bj = blocks[c.key.eblock];
  const Vec2& p = bi.vertices[c.key.vertex];
  const Vec2 a = edge_start(bj, c.key.edge), b = edge_end(bj, c.key.edge);
  const double l = (b - a).norm();
  const Vec2 t = (b - a) / l;

  // Normal: d_n = S / l with S = (a - p) x (b - p) > 0 when p is inside block j
  // (Shi 1988, the determinant form of the distance of P1 to P2P3); linearized
  // in the displacements u = T D of p, a and b.
  const double S = (a - p).x() * (b - p).y() - (a - p).y() * (b - p).x();
  h.dn0 = S / l;
  h.ni = displacement_matrix(bi.centroid, p).transpose() * perp(b - a) / l;
  h.nj = -(displacement_matrix(bj.centroid, a).transpose() * perp(b - p) +
           displacement_matrix(bj.centroid, b).transpose() * perp(p - a)) / l;

  // Shear: d_t = (P0P1 . P2P3)/l + H^T D_i + G^T D_j (the seed's eqs. 23-24, 27),
  // P0 the locking point on the entrance edge.
  const Vec2 p0 = a + c.locking_ratio * (b - a);
  h.dt0 = t.dot(p - p0);
  h.ti = displacement_matrix(bi.centroid, p).transpose() * t;
  h.tj = -displacement_matrix(bj.centroid, p0).transpose() * t;

  // Springs: penalty (eq. 17, one value for every contact point), or the joint
  // stiffness per unit area times the contact's tributary length l_t (its
  // length for an edge-edge contact, point_tributary_length for a point
  // contact), so that the joint's per-area response holds on every contact
  // and a contact's springs do not jump when it changes kind. Measured
  // (docs/contacts.md, "Springs of a joint on point contacts"): taking the
  // contact length, a column of the seed's slope that rose 3.4 cm off one base
  // corner turned its other base contact from edge-edge into a point contact,
  // whose shear spring jumped from the joint's 5e8 to the penalty's 1.6e11 N/m
  // with the stretch it had: the contact slid, and the settled slope depended
  // on whether the contact search reached the lifted corner.
  const JointSet& js = joint_sets_[c.joint_set];
  const double lt = c.tributary_length > 0.0 ? c.tributary_length : c.length;  // [length]
  h.pn = (js.normal_stiffness && lt > 0.0) ? *js.normal_stiffness * lt : penalty_;
  h.ps = (js.shear_stiffness && lt > 0.0) ? *js.shear_stiffness * lt
                                          : penalty_ / settings_.shear_normal_ratio;
  // A creep law's instantaneous spring E1 [stress/length] is the joint's elastic
  // shear stiffness, so a run reproduces the law's instantaneous response.
  if (js.law && lt > 0.0)
    if (const auto e1 = js.law->instantaneous_stiffness()) h.ps = *e1 * lt;
  // Dashpots c = 2 zeta sqrt(k m) beside the springs (JointSet::restitution),
  // m the reduced mass m_i m_j / (m_i + m_j) of the two blocks: the mass that
  // oscillates on the contact spring (the moving block's own mass against a
  // held one, infinite; one block's mass where the other's is unknown, 0).
  h.cn = h.cs = 0.0;
  h.reduced_mass = reduced_mass(bi.mass, bj.mass);
  if (js.restitution) {
    const double zeta = restitution_damping_ratio(*js.restitution);
    h.cn = 2.0 * zeta * std::sqrt(h.pn * h.reduced_mass);
    h.cs = 2.0 * zeta * std::sqrt(h.ps * h.reduced_mass);
  }
  h.tan_phi = std::tan(js.friction_angle * std::numbers::pi / 180.0);
  h.cohesion = c.intact ? js.cohesion : 0.0;
  h.tensile_strength = c.intact ? js.tensile_strength : 0.0;
}

void ContactSystem::stick(std::span<const BlockView> blocks, size_t c) {
  // Sliding -> locked where the vertex stood at the step start p. By default
  // (Shi's rule) the shear spring restarts unstretched there. With
  // ContactSettings::stick_keeps_force it keeps the friction force F the
  // contact slid against, as an elastic-plastic joint keeps its elastic shear
  // displacement: the locking point P0 goes behind p by the stretch that
  // carries F, P0 = p - s t with s = d F / k_s (d the slide direction, t the
  // edge direction). Measured trade (docs/contacts.md, "Why the iteration does
  // not settle"): far fewer iterates and cuts on walls and slopes at the
  // friction limit; a creeping slope at its limit takes other, step-dependent
  // paths.
  Contact& r = work_[c];
  Hot& h = hot_[c];
  const BlockView& eb = blocks[r.key.eblock];
  const Vec2 a = edge_start(eb, r.key.edge), b = edge_end(eb, r.key.edge);
  const double friction = std::max(h.normal_force, 0.0) * h.tan_phi + h.cohesion * r.length;
  const bool keep = step_dynamic_ && settings_.stick_keeps_force_dynamic ? *settings_.stick_keeps_force_dynamic
                                                                          : settings_.stick_keeps_force;
  const double stretch = keep ? r.slide_direction * friction / shear_stiffness(c) : 0.0;
  r.locking_ratio = line_ratio(a, b, blocks[r.key.vblock].vertices[r.key.vertex]) -
                    stretch / (b - a).norm();
  r.state = ContactState::locked;
  prepare(blocks, r, h);
}

void ContactSystem::lock_at_touch(std::span<const BlockView> blocks, size_t c, double flight) {
  // The locking point moves along the entrance edge by the tangential motion
  // before the touch, so the spring's stretch counts from there.
  Contact& r = work_[c];
  const BlockView& eb = blocks[r.key.eblock];
  r.locking_ratio += flight / (edge_end(eb, r.key.edge) - edge_start(eb, r.key.edge)).norm();
  prepare(blocks, r, hot_[c]);
}

double ContactSystem::normal_dashpot(size_t c) const {
  return step_dt_ > 0.0 && step_dynamic_ ? hot_[c].cn / step_dt_ : 0.0;
}

double ContactSystem::shear_dashpot(size_t c) const {
  return step_dt_ > 0.0 && step_dynamic_ ? hot_[c].cs / step_dt_ : 0.0;
}

double ContactSystem::reversal_stiffness(size_t c) const {
  // The smallest backward slip of a sliding contact that counts as a reversal
  // is f_res / k, the slip a force residual f_res moves the vertex by. Static
  // steps, or unset: Shi's shear spring k_s. Dynamic steps
  // (ContactSettings::reversal_at_normal_resolution): the normal spring p_n
  // plus the step's inertia on the contact, m_red / (beta dt^2) (the Newmark
  // term the host adds to the block's stiffness; m_red the reduced mass of the
  // two blocks). Measured (docs/contacts.md, "Friction that pushed"): with a
  // soft joint f_res / k_s was 1e-4 m on the seed's slope, more than a small
  // step's slip, so a vertex moving backwards kept its friction force pushing
  // it on, and the slope settled at 1 ms but never at 0.25 ms. Measured
  // (docs/contacts.md, "Contacts that stop"): with p_n alone the resolution is
  // a fixed length while the backward slip of a contact whose friction exceeds
  // its drive shrinks as dt^2 (the inertia holds it): contacts that had
  // stopped stayed sliding, more of them the smaller the step (the damped
  // brick wall: 41 at dt 31 us, 539 at 1.95 us), and the joints' shear
  // displacement did not converge.
  const Hot& h = hot_[c];
  if (!(settings_.reversal_at_normal_resolution && step_dynamic_)) return shear_stiffness(c);
  return h.pn + h.reduced_mass * step_inertia_;
}

double ContactSystem::shear_stiffness(size_t c) const {
  // Creep compliance folded into the spring: k_eff = k / (1 + k c) (laws/contact_rheology.hpp).
  const double k = hot_[c].ps;
  return k / (1.0 + k * seams_[c].compliance);
}

std::optional<laws::Scheme> ContactSystem::scheme_used(int js) const {
  if (js < 0 || js >= static_cast<int>(law_steps_.size()) || !law_steps_[js].active)
    return std::nullopt;
  return law_steps_[js].scheme;
}

const laws::StepConstants& ContactSystem::step_constants_of(size_t c) const {
  const LawStep& ls = law_steps_[work_[c].joint_set];
  return hot_[c].creep_from_rest ? ls.from_rest : ls.main;
}

void ContactSystem::linearize(size_t c, double tau_guess) {
  // Delta d_c = h + c tau_e (laws/contact_rheology.hpp) with tau = F / l_t:
  // locking point shifted by h, compliance c / l_t in force terms.
  const Contact& r = work_[c];
  const laws::Linearization lin = joint_sets_[r.joint_set].law->linearize(
      step_constants_of(c), work_rheology_[r.rheology], hot_[c].tau_start, tau_guess);
  seams_[c] = {-lin.h, lin.c / r.tributary_length};
}

double ContactSystem::time_to_failure() const {
  double t = std::numeric_limits<double>::infinity();
  for (const Contact& r : committed_)
    if (r.state == ContactState::locked && r.rheology >= 0 && r.tributary_length > 0.0 &&
        !r.creep_failed && joint_sets_[r.joint_set].law)
      t = std::min(t, joint_sets_[r.joint_set].law->time_to_failure(
                          committed_rheology_[r.rheology], r.shear_force / r.tributary_length));
  return t;
}

void ContactSystem::fail_law(size_t c) {
  // docs/rheology-in-dda.md, "Failure": a residual frictional joint from now on.
  Contact& r = work_[c];
  Hot& h = hot_[c];
  h.law_failed = true;
  r.creep_failed = true;
  if (r.rheology >= 0) work_rheology_[r.rheology] = {};  // no history left
  r.intact = false;
  h.cohesion = 0.0;
  h.tensile_strength = 0.0;
  seams_[c] = {};
}

void ContactSystem::begin_step(std::span<const BlockView> blocks, double max_displacement,
                               double dt, bool dynamic, double inertia) {
  step_dynamic_ = dynamic;
  const int nb = static_cast<int>(blocks.size());
  // Half model size w0 [length].
  Box model;
  model.lo = Vec2::Constant(std::numeric_limits<double>::infinity());
  model.hi = -model.lo;
  boxes_.resize(nb);
  for (int i = 0; i < nb; ++i) {
    const Box b = bounding_box(blocks[i], 0.0);
    model.lo = model.lo.cwiseMin(b.lo);
    model.hi = model.hi.cwiseMax(b.hi);
  }
  const double w0 = nb > 0 ? 0.5 * (model.hi - model.lo).maxCoeff() : 0.0;
  allowed_penetration_ = settings_.penetration_ratio * w0;
  double d0 = std::max(settings_.search_factor * max_displacement, settings_.min_search_distance);
  if (!(d0 > 0.0)) d0 = settings_.search_factor * 0.01 * w0;  // g2 = 0.01 when the host gives none

  for (int i = 0; i < nb; ++i) boxes_[i] = bounding_box(blocks[i], 0.5 * d0);
  const auto& pairs = broad_.find_pairs(boxes_);

  previous_keys_.resize(committed_.size());
  for (size_t k = 0; k < committed_.size(); ++k) previous_keys_[k] = committed_[k].key;
  const std::vector<DetectedContact> found =
      detect_contacts(blocks, pairs, {d0, settings_.angle_tolerance, allowed_penetration_}, previous_keys_);

  // Transfer: the same key keeps its record; otherwise the same vertex on an
  // adjacent edge of the same block inherits it (the vertex slid over a corner).
  const size_t n = found.size();
  std::vector<int> from(n, -1);
  std::vector<char> used(committed_.size(), 0);
  auto find_key = [&](const ContactKey& k) -> int {
    auto it = std::lower_bound(previous_keys_.begin(), previous_keys_.end(), k);
    return (it != previous_keys_.end() && *it == k) ? static_cast<int>(it - previous_keys_.begin())
                                                    : -1;
  };
  for (size_t c = 0; c < n; ++c)
    if (int o = find_key(found[c].key); o >= 0) from[c] = o, used[o] = 1;
  int transferred = 0;
  for (size_t c = 0; c < n; ++c) {
    if (from[c] >= 0) { ++transferred; continue; }
    const ContactKey& k = found[c].key;
    const int ne = static_cast<int>(blocks[k.eblock].vertices.size());
    for (int de : {-1, 1}) {
      const int o = find_key({k.vblock, k.vertex, k.eblock, wrap(k.edge + de, ne)});
      if (o >= 0 && !used[o]) { from[c] = o; used[o] = 1; ++transferred; break; }
    }
  }

  work_.clear();
  work_rheology_.clear();
  hot_.clear();
  for (size_t c = 0; c < n; ++c) {
    const DetectedContact& d = found[c];
    const BlockView& eb = blocks[d.key.eblock];
    const int js = eb.edge_joint_set.empty() ? 0 : eb.edge_joint_set[d.key.edge];
    if (js < 0 || js >= static_cast<int>(joint_sets_.size()))
      throw std::out_of_range("block " + std::to_string(d.key.eblock) + " edge " +
                              std::to_string(d.key.edge) + ": joint set " + std::to_string(js) +
                              " does not exist (" + std::to_string(joint_sets_.size()) + " defined)");
    Contact rec;
    const Contact* old = from[c] >= 0 ? &committed_[from[c]] : nullptr;
    if (old) {
      rec = *old;
      if (old->key.edge != d.key.edge) {
        // Moved to an adjacent edge: the locking point goes to its projection on the new edge.
        const Vec2 a0 = edge_start(eb, old->key.edge), b0 = edge_end(eb, old->key.edge);
        const Vec2 p0 = a0 + old->locking_ratio * (b0 - a0);
        rec.locking_ratio = projection_ratio(edge_start(eb, d.key.edge), edge_end(eb, d.key.edge), p0);
      }
    } else {
      rec.state = ContactState::open;
    }
    // Stress at the end of the last step, tau = F / l_t with that step's
    // tributary length: tau = E1 x the spring's stretch, continuous when the
    // contact's length changes (change of kind, transfer) [stress].
    const double tau_old =
        (old && old->tributary_length > 0.0) ? old->shear_force / old->tributary_length : 0.0;
    rec.key = d.key;
    rec.kind = d.kind;
    rec.length = d.length;
    rec.joint_set = js;
    const Vec2 a = edge_start(eb, d.key.edge), b = edge_end(eb, d.key.edge);
    const Vec2& p = blocks[d.key.vblock].vertices[d.key.vertex];
    rec.tributary_length = d.length > 0.0
                               ? d.length
                               : point_tributary_length(blocks[d.key.vblock], d.key.vertex,
                                                        (b - a).normalized());
    // An open contact locks where the vertex projects at the start of the step.
    if (rec.state == ContactState::open) rec.locking_ratio = line_ratio(a, b, p);
    Hot h;
    prepare(blocks, rec, h);
    if (!old) {
      // A new contact deeper than the allowed penetration is no contact: the
      // vertex lies inside the other block beyond this edge (it belongs to
      // another face, e.g. a step corner within the search distance of the
      // next block's base).
      if (h.dn0 > allowed_penetration_) continue;
      rec.id = next_id_++;
      // A new contact that already touches (to round-off: 1e-9 of the edge
      // length) or penetrates starts closed: blocks built touching each other
      // carry load from the first iterate instead of closing row by row.
      if (h.dn0 > -1e-9 * (b - a).norm()) rec.state = ContactState::locked;
    }
    // Rheology slot: kept on transfer and change of kind, created for a new
    // contact on a joint set with a law.
    if (joint_sets_[js].law) {
      laws::RheologyState st;
      if (old && old->rheology >= 0) st = committed_rheology_[old->rheology];
      rec.rheology = static_cast<int>(work_rheology_.size());
      work_rheology_.push_back(st);
    } else {
      rec.rheology = -1;
    }
    h.start_state = rec.state;
    // The dashpot counts the step's approach from the step start, or for a
    // contact open across a gap from where it touches: it never pushes a
    // separating contact (one open at the step start but still overlapping, after
    // a rebound opened it, moves apart from d_n0, not from 0).
    h.dn_ref = rec.state == ContactState::open ? std::max(h.dn0, 0.0) : h.dn0;
    // Creep from rest: the contact was not locked at the end of the last step
    // (new, open or sliding), so its force before this step is not defined.
    h.creep_from_rest = !(old && old->state == ContactState::locked);
    h.tau_start = (rec.rheology >= 0 && rec.tributary_length > 0.0 && !h.creep_from_rest)
                      ? tau_old
                      : 0.0;
    h.flips = h.refinements = 0;
    h.normal_force = rec.state == ContactState::open ? 0.0 : rec.normal_force;
    work_.push_back(rec);
    hot_.push_back(h);
  }
  seams_.assign(work_.size(), ShearSeam{});
  work_creep_.assign(work_.size(), 0.0);

  // Law constants, once per joint set and step (never per contact). The
  // automatic scheme looks at the stiffest spring per unit area of the set.
  law_steps_.assign(joint_sets_.size(), LawStep{});
  const bool any_law = std::any_of(joint_sets_.begin(), joint_sets_.end(),
                                   [](const JointSet& j) { return j.law != nullptr; });
  if (dt > 0.0 && any_law) {
    std::vector<double> k_area(joint_sets_.size(), 0.0);
    for (size_t c = 0; c < work_.size(); ++c)
      if (work_[c].rheology >= 0 && work_[c].tributary_length > 0.0)
        k_area[work_[c].joint_set] =
            std::max(k_area[work_[c].joint_set], hot_[c].ps / work_[c].tributary_length);
    for (size_t j = 0; j < joint_sets_.size(); ++j) {
      const auto& law = joint_sets_[j].law;
      if (!law) continue;
      LawStep& ls = law_steps_[j];
      ls.active = true;
      ls.scheme = settings_.scheme ? *settings_.scheme : automatic_scheme(*law, k_area[j], dt);
      ls.main = law->step_constants(dt, ls.scheme);
      ls.from_rest = law->step_constants(dt, laws::Scheme::implicit);
    }
    for (size_t c = 0; c < work_.size(); ++c)
      if (work_[c].rheology >= 0 && work_[c].tributary_length > 0.0 && !work_[c].creep_failed)
        linearize(c, hot_[c].tau_start);
  }
  step_dt_ = dt;
  step_inertia_ = inertia;
  step_max_penetration_ = 0.0;
  force_scale_ = 0.0;
  for (const Contact& c : committed_) force_scale_ = std::max(force_scale_, std::abs(c.normal_force));
  stats_ = {static_cast<int>(pairs.size()), static_cast<int>(work_.size()), transferred, d0};
}

void ContactSystem::assemble(std::span<const BlockView>, SystemSink& sink) const {
  for (size_t c = 0; c < work_.size(); ++c) {
    const Contact& r = work_[c];
    const int i = r.key.vblock, j = r.key.eblock;
    if (r.state == ContactState::open) {
      // A zero block keeps the matrix pattern of the pair through the
      // open-close iteration, so the host can reuse its symbolic factorisation.
      sink.add_stiffness(i, j, Mat6::Zero());
      continue;
    }
    const Hot& h = hot_[c];
    // Normal spring: energy p_n d_n^2 / 2 (Shi 1988).
    Mat6 kii = h.pn * h.ni * h.ni.transpose();
    Mat6 kjj = h.pn * h.nj * h.nj.transpose();
    Mat6 kij = h.pn * h.ni * h.nj.transpose();
    Vec6 fi = -h.pn * h.dn0 * h.ni;
    Vec6 fj = -h.pn * h.dn0 * h.nj;
    if (const double kd = normal_dashpot(c); kd > 0.0) {
      // Normal dashpot, implicit over the step: force (c/dt)(d_n - d_ref).
      kii += kd * h.ni * h.ni.transpose();
      kjj += kd * h.nj * h.nj.transpose();
      kij += kd * h.ni * h.nj.transpose();
      fi -= kd * (h.dn0 - h.dn_ref) * h.ni;
      fj -= kd * (h.dn0 - h.dn_ref) * h.nj;
    }
    if (r.state == ContactState::locked) {
      // Shear spring: the seed's eqs. 28-29, with the locking point shifted by
      // the creep seam (zero without a law).
      const double ps = shear_stiffness(c);
      const double d0 = h.dt0 + seams_[c].locking_shift;
      kii += ps * h.ti * h.ti.transpose();
      kjj += ps * h.tj * h.tj.transpose();
      kij += ps * h.ti * h.tj.transpose();
      fi -= ps * d0 * h.ti;
      fj -= ps * d0 * h.tj;
      // Shear dashpot on the step's tangential motion: force (c_s/dt) slip.
      if (const double kd = shear_dashpot(c); kd > 0.0) {
        kii += kd * h.ti * h.ti.transpose();
        kjj += kd * h.tj * h.tj.transpose();
        kij += kd * h.ti * h.tj.transpose();
      }
    } else {
      // Sliding: Mohr-Coulomb friction F = N tan(phi) + c l against the slip
      // direction, N from the last iterate.
      const double f = std::max(h.normal_force, 0.0) * h.tan_phi + h.cohesion * r.length;
      fi -= r.slide_direction * f * h.ti;
      fj -= r.slide_direction * f * h.tj;
    }
    sink.add_stiffness(i, i, kii);
    sink.add_stiffness(j, j, kjj);
    sink.add_stiffness(i, j, kij);
    sink.add_load(i, fi);
    sink.add_load(j, fj);
  }
}

CheckResult ContactSystem::check(std::span<const BlockView> blocks, const Eigen::VectorXd& D) {
  assert(D.size() == 6 * static_cast<Eigen::Index>(blocks.size()));
  CheckResult res;
  // Force resolution: forces below this are zero for the state decisions, so
  // contacts that carry (almost) nothing - the vertical joints of a wall - do
  // not flip on round-off.
  const double f_res = settings_.force_resolution * force_scale_;
  double scale = 0.0;
  for (size_t c = 0; c < work_.size(); ++c) {
    Contact& r = work_[c];
    Hot& h = hot_[c];
    h.assembled_normal_force = h.normal_force;  // energy balance: the friction just solved with
    const auto Di = D.segment<6>(6 * r.key.vblock);
    const auto Dj = D.segment<6>(6 * r.key.eblock);
    const double dn = h.dn0 + h.ni.dot(Di) + h.nj.dot(Dj);
    const double slip = h.ti.dot(Di) + h.tj.dot(Dj);  // tangential motion this step [length]
    const double dt = h.dt0 + seams_[c].locking_shift + slip;
    // The states follow the springs alone (the overlap and the shear spring's
    // stretch), as in Cundall & Strack's spring-dashpot contact: a contact
    // dashpot (JointSet::restitution) adds its force c rate beside the spring
    // of a closed (normal) or locked (shear) contact, but neither opens, closes,
    // nor makes a contact slide, and friction is N tan(phi) of the spring's N.
    // Measured (docs/contacts.md, "Contact damping"): deciding on the total
    // force instead, the dashpot's transient force at an impact (c v, hundreds
    // of times the block's weight) locks the shear spring with a stretch that
    // the weight's friction cannot hold afterwards, and the drop on an incline
    // ends 1.24-1.43 mm down the slope depending on the step.
    const double N = h.pn * dn;
    r.penetration = dn;
    const ContactState before = r.state;
    bool refine = false;  // friction force from a stale normal force
    switch (r.state) {
      case ContactState::open:
        if (N > f_res) {
          // Closes; Mohr-Coulomb decides at once whether it holds or slides (a
          // vertex arriving with tangential speed would otherwise be caught by
          // a fully stretched shear spring for one iterate). Across a gap g0 =
          // -d_n0 the vertex touches after the share f = g0 / (g0 + d_n) of the
          // step's approach (linear in the step); the tangential motion before
          // that, f slip, is flight, not stretch of the spring: the spring locks
          // where the vertex touches. Counting it (Shi's rule: the locking point
          // at the step-start projection) made the outcome of an impact depend
          // on where in its step the contact was reached (docs/contacts.md,
          // "Contact damping": a block dropped on an incline slid at the impact
          // at some steps and not at others). Dynamic analysis only
          // (ContactSettings::lock_at_touch).
          const double gap = std::max(-h.dn0, 0.0);
          const double flight =
              (settings_.lock_at_touch && step_dynamic_ && gap > 0.0) ? gap / (gap + dn) * slip : 0.0;
          const double S = shear_stiffness(c) * (dt - flight);
          if (std::abs(S) > N * h.tan_phi + h.cohesion * r.length + f_res) {
            r.state = ContactState::sliding;
            r.slide_direction = S >= 0.0 ? 1 : -1;
          } else {
            r.state = ContactState::locked;
            if (flight != 0.0) lock_at_touch(blocks, c, flight);
          }
        }
        break;
      case ContactState::locked:
      case ContactState::sliding:
        if (N < -h.tensile_strength * r.length - f_res) {
          r.state = ContactState::open;
        } else if (r.state == ContactState::locked) {
          // Mohr-Coulomb: slip when |F_T| > N tan(phi) + c l.
          const double S = shear_stiffness(c) * dt;
          if (std::abs(S) > N * h.tan_phi + h.cohesion * r.length + f_res) {
            r.state = ContactState::sliding;
            r.slide_direction = dt >= 0.0 ? 1 : -1;
          }
        } else if (reversal_stiffness(c) * slip * r.slide_direction < -f_res) {
          // The vertex moves against the friction direction assumed: it sticks
          // where it stood at the start of the step (stick). The test resolves
          // a backward slip of f_res / k with k the stiffness that holds the
          // vertex's tangential motion (reversal_stiffness).
          stick(blocks, c);
        } else {
          // The friction force N tan(phi) came from the last iterate's N.
          refine = std::abs(N - h.normal_force) >
                   std::max(settings_.friction_tolerance *
                                std::max(std::abs(N), std::abs(h.normal_force)),
                            f_res);
        }
        break;
    }
    if (r.state != before) {
      if (h.flips >= settings_.max_flips && r.state != ContactState::locked) {
        // Anti-chattering: a contact that already changed max_flips times in
        // this step (typically a vertex that stops within the step: sliding
        // reverses it, locking needs more than friction to stop it) may only
        // go to the most constrained state, locked, for the rest of the step.
        // Any Mohr-Coulomb excess lasts one step: the next step starts from it.
        if (before == ContactState::locked) {
          r.state = before;
        } else {
          if (before == ContactState::sliding) stick(blocks, c);
          r.state = ContactState::locked;
        }
      }
      if (r.state != before) {
        ++h.flips;
        ++res.state_changes;
        if (before == ContactState::open) ++res.closed;
        else if (r.state == ContactState::open) ++res.opened;
        else if (r.state == ContactState::sliding) ++res.slipped;
        else ++res.stuck;
      }
    } else if (refine && h.refinements < settings_.max_refinements) {
      ++h.refinements;
      ++res.state_changes;
      ++res.refinements;
    }
    // The normal force that drives friction in the next iterate. A contact that
    // just closed has N from a trial without its spring (the whole free
    // approach of the step as penetration): start its friction from zero and
    // let the refinement above bring it to its own N.
    h.normal_force = (r.state == ContactState::open || before == ContactState::open) ? 0.0 : N;
    if (r.state != ContactState::open) {
      res.max_penetration = std::max(res.max_penetration, dn);
      scale = std::max(scale, std::abs(N));
    }
    // A piecewise-affine law (Nishihara's threshold): take the piece that holds
    // at this iterate's stress; a change asks for another iteration (bounded
    // by max_refinements, so the switch cannot chatter).
    if (r.state == ContactState::locked && r.rheology >= 0 && r.tributary_length > 0.0 &&
        law_steps_[r.joint_set].active && !r.creep_failed &&
        !joint_sets_[r.joint_set].law->is_linear()) {
      const ShearSeam before_seam = seams_[c];
      const double tau =
          shear_stiffness(c) * (h.dt0 + seams_[c].locking_shift + slip) / r.tributary_length;
      const laws::ContactRheology& law = *joint_sets_[r.joint_set].law;
      if (law.failure_in_step(step_constants_of(c), work_rheology_[r.rheology], h.tau_start, tau)) {
        // The law fails within the step at this stress (damage 1, docs/rheology-in-dda.md,
        // "Failure"): the joint's creep strength is gone. It becomes a residual
        // frictional joint - elastic spring, no creep, no cohesion or tensile
        // strength - and the next iterate lets Mohr-Coulomb decide whether its
        // friction holds.
        fail_law(c);
        ++res.state_changes;
        ++res.slipped;
        continue;
      }
      linearize(c, tau);
      if (law.linearity() == laws::Linearity::nonlinear) {
        // Newton (docs/rheology-in-dda.md, "Nonlinear laws"): the iterate was
        // solved with the tangent at the last stress; the law's increment at
        // this stress, Delta d_c(tau) = h + c tau of the new tangent, differs
        // from that model by e [length], which moves the stress by about
        // k_eff e / l_t. Another iterate while that exceeds the tolerance.
        const double lt = r.tributary_length;
        const double model = -before_seam.locking_shift + before_seam.compliance * lt * tau;
        const double actual = -seams_[c].locking_shift + seams_[c].compliance * lt * tau;
        const double stress_error = shear_stiffness(c) * std::abs(actual - model) / lt;
        if (stress_error > settings_.creep_newton_tolerance * std::max(std::abs(tau), f_res / lt) &&
            h.newton < settings_.max_creep_newton) {
          ++h.newton;
          ++res.state_changes;
          ++res.refinements;
        }
      } else if ((seams_[c].compliance != before_seam.compliance ||
                  seams_[c].locking_shift != before_seam.locking_shift) &&
                 h.refinements < settings_.max_refinements) {
        ++h.refinements;
        ++res.state_changes;
        ++res.refinements;
      }
    }
  }
  force_scale_ = scale;
  step_max_penetration_ = res.max_penetration;
  return res;
}

void ContactSystem::end_step(std::span<const BlockView> blocks, const Eigen::VectorXd& D) {
  assert(D.size() == 6 * static_cast<Eigen::Index>(blocks.size()));
  double max_pen = 0.0;
  stored_before_ = stored_energy(committed_, committed_work_);  // energy balance
  step_work_.resize(work_.size());                              // energy balance
  for (size_t c = 0; c < work_.size(); ++c) {
    Contact& r = work_[c];
    const Hot& h = hot_[c];
    const auto Di = D.segment<6>(6 * r.key.vblock);
    const auto Dj = D.segment<6>(6 * r.key.eblock);
    const double dn = h.dn0 + h.ni.dot(Di) + h.nj.dot(Dj);
    const double slip = h.ti.dot(Di) + h.tj.dot(Dj);
    const double dt = h.dt0 + seams_[c].locking_shift + slip;
    r.penetration = dn;
    r.creep_state = r.rheology >= 0 ? CreepState::idle : CreepState::none;
    step_work_[c] = {h.pn, h.ps, h.dn0, dn, h.dt0, slip, h.start_state,  // energy balance
                     r.slide_direction * (std::max(h.assembled_normal_force, 0.0) * h.tan_phi +
                                          h.cohesion * r.length),
                     r.state != ContactState::open ? normal_dashpot(c) * (dn - h.dn_ref) : 0.0,
                     r.state == ContactState::locked ? shear_dashpot(c) * slip : 0.0};
    switch (r.state) {
      case ContactState::open:
        if (h.law_failed) ++creep_counters_[r.joint_set].failures;  // failed at an iterate (check)
        r.normal_force = r.shear_force = 0.0;
        if (h.start_state != ContactState::open) r.intact = false;
        break;
      case ContactState::locked:
        r.normal_force = h.pn * dn;
        r.shear_force = shear_stiffness(c) * dt;
        r.shear_displacement += slip;
        max_pen = std::max(max_pen, dn);
        if (r.rheology >= 0 && r.tributary_length > 0.0 && law_steps_[r.joint_set].active &&
            !r.creep_failed) {
          // Advance the history from the step-start state with the step's end
          // stress tau = F / l_t, move the locking point by the creep increment
          // along the entrance edge (the seed's eqs. 22-29) and take the force
          // from the spring's remaining stretch.
          const laws::RheologyState old = work_rheology_[r.rheology];
          const double creep = joint_sets_[r.joint_set].law->advance(
              step_constants_of(c), old, h.tau_start, r.shear_force / r.tributary_length,
              work_rheology_[r.rheology]);
          CreepCounters& counters = creep_counters_[r.joint_set];
          counters.contact_time += step_dt_;
          if (!r.has_crept) ++counters.contacts;
          r.has_crept = true;
          r.creep_state = CreepState::creeping;
          if (work_rheology_[r.rheology].failed()) {
            // The law failed within the step at the converged stress although no
            // iterate saw it (e.g. anti-chattering): the joint becomes a
            // residual frictional joint now, without this step's creep; the
            // next step's Mohr-Coulomb check decides whether it holds.
            fail_law(c);
            work_creep_[c] = 0.0;
          } else {
          const BlockView& eb = blocks[r.key.eblock];
          r.locking_ratio += creep / (edge_end(eb, r.key.edge) - edge_start(eb, r.key.edge)).norm();
          r.shear_force = h.ps * (h.dt0 + slip - creep);
          work_creep_[c] = creep;
          r.creep_displacement += creep;
          }
        }
        if (h.law_failed) ++creep_counters_[r.joint_set].failures;
        break;
      case ContactState::sliding: {
        if (h.law_failed) ++creep_counters_[r.joint_set].failures;  // failed at an iterate (check)
        r.normal_force = h.pn * dn;
        r.shear_force = r.slide_direction *
                        (std::max(r.normal_force, 0.0) * h.tan_phi + h.cohesion * r.length);
        r.shear_displacement += slip;
        r.intact = false;
        max_pen = std::max(max_pen, dn);
        // The locking point follows the vertex: its projection on the displaced edge.
        const BlockView& bi = blocks[r.key.vblock];
        const BlockView& bj = blocks[r.key.eblock];
        const Vec2& p = bi.vertices[r.key.vertex];
        const Vec2 a = edge_start(bj, r.key.edge), b = edge_end(bj, r.key.edge);
        const Vec2 p1 = p + displacement_matrix(bi.centroid, p) * Di;
        const Vec2 a1 = a + displacement_matrix(bj.centroid, a) * Dj;
        const Vec2 b1 = b + displacement_matrix(bj.centroid, b) * Dj;
        r.locking_ratio = line_ratio(a1, b1, p1);
        break;
      }
    }
  }
  last_max_penetration_ = max_pen;
  // Penetration control: raise the penalty for the next steps.
  if (max_pen > allowed_penetration_ &&
      penalty_ * settings_.penalty_raise <= settings_.penalty * settings_.penalty_max_factor)
    penalty_ *= settings_.penalty_raise;
  // History rules: an open or sliding contact loses its creep history (the
  // spring relocks unstretched, so the law restarts from rest).
  for (const Contact& r : work_)
    if (r.rheology >= 0 && r.state != ContactState::locked) work_rheology_[r.rheology] = {};
  committed_.swap(work_);
  committed_rheology_.swap(work_rheology_);
  committed_creep_.swap(work_creep_);
  committed_work_.swap(step_work_);  // energy balance
  work_.clear();
  work_rheology_.clear();
  work_creep_.clear();
}

bool ContactSystem::extrapolate(const ContactSystem& coarse) {
  const std::vector<Contact>& cc = coarse.committed_;
  if (cc.size() != committed_.size() || coarse.penalty_ != penalty_) return false;
  for (size_t k = 0; k < committed_.size(); ++k) {
    const Contact& f = committed_[k];
    const Contact& c = cc[k];
    if (!(f.key == c.key) || f.joint_set != c.joint_set || f.state != c.state ||
        f.intact != c.intact || (f.rheology >= 0) != (c.rheology >= 0) ||
        f.creep_failed != c.creep_failed ||
        (f.state == ContactState::sliding && f.slide_direction != c.slide_direction))
      return false;
  }
  // Richardson: y_f - y = C dt^2/2 and y_c - y = C dt^2 to leading order, so
  // 2 y_f - y_c cancels the leading error (docs/speed-accuracy.md).
  auto richardson = [](double& fine, double c) { fine = 2.0 * fine - c; };
  for (size_t k = 0; k < committed_.size(); ++k) {
    Contact& f = committed_[k];
    const Contact& c = cc[k];
    richardson(f.locking_ratio, c.locking_ratio);
    richardson(f.normal_force, c.normal_force);
    richardson(f.shear_force, c.shear_force);
    richardson(f.shear_displacement, c.shear_displacement);
    richardson(f.penetration, c.penetration);
    richardson(f.creep_displacement, c.creep_displacement);
    if (f.rheology < 0) continue;
    laws::RheologyState& qf = committed_rheology_[f.rheology];
    const laws::RheologyState& qc = coarse.committed_rheology_[c.rheology];
    // Both runs start from the same history, so the fine run's creep over the
    // step is the coarse one's plus qf.creep() - qc.creep(); the extrapolated
    // increment is 2 (that) - coarse's.
    const double creep_fine_minus_coarse = qf.creep() - qc.creep();
    for (size_t i = 0; i < qf.q.size(); ++i) richardson(qf.q[i], qc.q[i]);
    // Damage of a damage law: extrapolated like the displacements, but never
    // to failure or below 0 by extrapolation (the fine value is kept then).
    if (const double d = 2.0 * qf.damage - qc.damage; d >= 0.0 && d < 1.0) qf.damage = d;
    committed_creep_[k] = coarse.committed_creep_[k] + 2.0 * creep_fine_minus_coarse;
  }
  return true;
}

void ContactSystem::abandon_step() {
  work_.clear();
  work_rheology_.clear();
  work_creep_.clear();
  hot_.clear();
  seams_.clear();
}

}  // namespace rheodda::contact
