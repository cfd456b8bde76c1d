// The contacts' terms of the energy balance of a run (docs/reference/engine.md, "Energy
// balance"; docs/reference/contacts.md, "Energy"): what the contact springs store after
// an accepted step and where the work the blocks did on them went during it.
//
// Energies are per unit thickness: [force x length], with "force" per unit
// thickness as everywhere in contact/ (J/m in SI).
//
// Every spring's end force acts over the whole step (DDA is implicit: forces
// are evaluated at the end of the step). For a linear spring k whose stretch
// goes from s0 to s1 = s0 + Delta the work it takes from the blocks is
//     F1 Delta = k s1 Delta = (k s1^2/2 - k s0^2/2) + k Delta^2/2,
// i.e. the change of its stored energy plus k Delta^2/2 >= 0: the time
// integration's dissipation (Shi's scheme). A spring attached during the step
// (a contact that closes) stored nothing at the start, so its whole
// F1 Delta - k s1^2/2 = k Delta^2/2 - k s0^2/2 is lost (s0 < 0 is the gap the
// end force acted over); a spring detached during the step (a contact that
// opens or slips) loses its start energy k s0^2/2 without doing any work.
#pragma once

namespace rheodda::contact {

/// Contact terms of the energy balance [force x length]: stored energies after
/// the last accepted step, and flows of that step (ContactSystem::energy).
struct ContactEnergy {
  // Stored at the end of the step.
  double normal = 0.0;  ///< sum of p_n d_n^2/2 over closed (locked or sliding) contacts
                        ///< (= N^2/(2 p_n) when the normal force is the spring's alone)
  double shear = 0.0;   ///< sum of F^2/(2 k_s) over locked contacts, k_s the elastic shear
                        ///< spring (for a creep law E1 l: the compliance fold k/(1 + k c)
                        ///< is the dashpot's share, counted in `creep`)
  // Flows of the step.
  double friction = 0.0;  ///< sum over sliding contacts of F slip: the friction force the
                          ///< final solve assembled (N tan(phi) + c l with the N of the
                          ///< iterate before it, signed along the slide direction) times the
                          ///< step's tangential motion; < 0 where the vertex moved against
                          ///< the assumed direction
  double creep = 0.0;     ///< sum over locked contacts with a law of F Delta d_c: the end
                          ///< force times the step's creep increment (dashpots; includes
                          ///< what the law's Kelvin springs store)
  double integration = 0.0;  ///< sum of k Delta^2/2 over the normal and shear springs
                             ///< attached through the whole step
  double damping = 0.0;   ///< contact dashpots (JointSet::restitution; else 0): the sum over
                          ///< closed contacts of the normal dashpot's end force times the
                          ///< step's approach d_n - d_n0, and over locked contacts of the
                          ///< shear dashpot's end force times the slip
  double closing = 0.0;   ///< springs attached during the step: k Delta^2/2 - k s0^2/2
                          ///< = F1 Delta - k s1^2/2 (the end force over the gap closed)
  double release = 0.0;   ///< springs detached during the step: k s0^2/2, their energy at
                          ///< the step start, released without work; and springs detached
                          ///< at its end by the commit's projection onto the Mohr-Coulomb
                          ///< envelope (a contact held locked outside it committed open, or
                          ///< locked at its strength): the end energy k s1^2/2 beyond what
                          ///< the committed state stores
  double restart = 0.0;   ///< energy the springs gained without work between the steps: the
                          ///< sum of k s0^2/2 over the springs attached at the step start
                          ///< (step-start geometry, this step's stiffness) minus the stored
                          ///< energy after the previous step (penalty raise, re-measured
                          ///< geometry, transfers, contacts appearing penetrated or vanishing,
                          ///< locking points reset)
};

}  // namespace rheodda::contact
