// Into a step (docs/reference/contacts.md, "Contact identity (transfer)"): contacts
// detected on the step-start geometry, each given the record of the same
// physical contact in the last step when there is one (its state, locking
// point, forces, creep history), new ones starting open or, already touching,
// locked.
#include "rheodda/contact/contact_system.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "contact_geometry.hpp"

namespace rheodda::contact {

void ContactSystem::begin_step(std::span<const BlockView> blocks, const StepContext& context) {
  step_.dynamic = context.dynamic;
  cycles_.reset();
  creep_error_wanted_ = context.creep_error_wanted;
  start_.retractable = false;
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
  double d0 = std::max(settings_.search_factor * context.max_displacement, settings_.min_search_distance);
  if (!(d0 > 0.0)) d0 = settings_.search_factor * 0.01 * w0;  // max_displacement_ratio = 0.01 when the host gives none

  for (int i = 0; i < nb; ++i) boxes_[i] = bounding_box(blocks[i], 0.5 * d0);
  const std::vector<std::pair<int, int>>* found_pairs = &broad_.find_pairs(boxes_);
  std::vector<std::pair<int, int>> kept_pairs;
  if (!removed_.empty()) {  // blocks removed by a stage (contact_edits.cpp) pair with nothing
    auto gone = [&](int b) { return b < static_cast<int>(removed_.size()) && removed_[b]; };
    for (const auto& p : *found_pairs)
      if (!gone(p.first) && !gone(p.second)) kept_pairs.push_back(p);
    found_pairs = &kept_pairs;
  }
  const auto& pairs = *found_pairs;

  const std::vector<Contact>& committed = records_.committed.contacts;
  previous_keys_.resize(committed.size());
  for (size_t k = 0; k < committed.size(); ++k) previous_keys_[k] = committed[k].key;
  const std::vector<DetectedContact> found =
      detect_contacts(blocks, pairs, {d0, settings_.angle_tolerance, allowed_penetration_}, previous_keys_);

  // Transfer: the same key keeps its record; otherwise the same vertex on an
  // adjacent edge of the same block inherits it (the vertex slid over a corner).
  const size_t n = found.size();
  std::vector<int> from(n, -1);
  std::vector<char> used(committed.size(), 0);
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

  records_.work.contacts.clear();
  records_.work.rheology.clear();
  step_.hot.clear();
  DetectionStats restart;  // its restart_* only
  for (size_t c = 0; c < n; ++c) {
    const DetectedContact& d = found[c];
    const BlockView& eb = blocks[d.key.eblock];
    const int js = eb.edge_joint_set.empty() ? 0 : eb.edge_joint_set[d.key.edge];
    if (js < 0 || js >= static_cast<int>(joint_sets_.size()))
      throw std::out_of_range("block " + std::to_string(d.key.eblock) + " edge " +
                              std::to_string(d.key.edge) + ": joint set " + std::to_string(js) +
                              " does not exist (" + std::to_string(joint_sets_.size()) + " defined)");
    Contact rec;
    const Contact* old = from[c] >= 0 ? &committed[from[c]] : nullptr;
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
    // The joint length the contact stands for, l_t (docs/reference/rheology-in-dda.md, "The
    // tributary length"): a point contact's from its vertex, (3) there; an edge-edge contact's
    // half the overlap l, never less than Q - l with Q that point length clipped to half the
    // entrance edge (4). As the overlap shrinks to nothing (two corners meeting) l_t tends to
    // Q instead of to zero: with l_t -> 0 the joint's springs (k l_t) lose their stiffness,
    // a stick locks such a spring F / k behind its vertex (kilometres away) and the change of
    // kind that follows starts that stretch on a point contact's spring, energy no force put
    // there (docs/notes/rock-mass-steps.md, "A mechanism stage that never rests").
    const double point = point_tributary_length(blocks[d.key.vblock], d.key.vertex, (b - a).normalized());
    rec.tributary_length =
        d.length > 0.0 ? std::max(d.length, std::min(point, 0.5 * (b - a).norm()) - d.length) : point;
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
      rec.id = records_.next_id++;
      // A new contact that already touches (to round-off: 1e-9 of the edge
      // length) or penetrates starts closed: blocks built touching each other
      // carry load from the first iterate instead of closing row by row.
      if (h.dn0 > -1e-9 * (b - a).norm()) rec.state = ContactState::locked;
    }
    // Rheology slot: kept on transfer and change of kind, created for a new
    // contact on a joint set with a law.
    if (joint_sets_[js].law) {
      laws::RheologyState st;
      if (old && old->rheology >= 0) st = records_.committed.rheology[old->rheology];
      rec.rheology = static_cast<int>(records_.work.rheology.size());
      records_.work.rheology.push_back(st);
    } else {
      rec.rheology = -1;
    }
    h.start_state = rec.state;
    {
      // Diagnosis (DetectionStats::restart_*): the springs' energy at the step
      // start against what the record stored at the end of the last step.
      double u0 = 0.0, u_old = 0.0;
      if (rec.state != ContactState::open) u0 += 0.5 * h.pn * h.dn0 * h.dn0;
      if (rec.state == ContactState::locked) u0 += 0.5 * h.ps * h.dt0 * h.dt0;
      if (old && from[c] < static_cast<int>(energy_.committed.size())) {
        const StepWork& w = energy_.committed[from[c]];
        if (old->state != ContactState::open) u_old += 0.5 * w.pn * old->penetration * old->penetration;
        if (old->state == ContactState::locked && w.ps > 0.0) u_old += 0.5 * old->shear_force * old->shear_force / w.ps;
      }
      if (u0 > u_old) {
        DetectionStats::Restart& cause = !old                        ? restart.restart_new
                                         : old->key.edge != d.key.edge ? restart.restart_edge
                                         : old->kind != d.kind         ? restart.restart_kind
                                                                       : restart.restart_same;
        ++cause.contacts;
        cause.energy += u0 - u_old;
        if (u0 - u_old > cause.largest) cause.largest = u0 - u_old, cause.largest_id = rec.id;
      }
    }
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
    records_.work.contacts.push_back(rec);
    step_.hot.push_back(h);
  }
  step_.seams.assign(records_.work.contacts.size(), ShearSeam{});
  records_.work.creep.assign(records_.work.contacts.size(), 0.0);

  start_laws(context.dt);
  step_.dt = context.dt;
  step_.inertia = context.inertia;
  step_.max_penetration = 0.0;
  step_.force_scale = 0.0;
  for (const Contact& c : committed) step_.force_scale = std::max(step_.force_scale, std::abs(c.normal_force));
  step_.force_cap = 0.0;
  for (const Hot& h : step_.hot) step_.force_cap = std::max(step_.force_cap, h.pn);
  step_.force_cap *= allowed_penetration_;
  stats_ = restart;
  stats_.candidate_pairs = static_cast<int>(pairs.size());
  stats_.contacts = static_cast<int>(records_.work.contacts.size());
  stats_.transferred = transferred;
  stats_.search_distance = d0;
}

}  // namespace rheodda::contact
