#include "rheodda/core/integrator.hpp"

#include <array>
#include <stdexcept>

#include "engine_impl.hpp"

namespace rheodda::core {

namespace {

// `automatic` is the scene's choice between the other two, by an estimate of their cost on the
// scene's initial state (scene/integrator_choice.hpp; docs/reference/explicit-step.md, "Automatic
// choice"): it has no trial of its own.
constexpr std::array<IntegratorEntry, 3> kIntegrators{{
    {Integrator::implicit, "implicit", &Engine::Impl::implicit_trial, nullptr},
    {Integrator::explicit_step, "explicit", &Engine::Impl::cycle_trial, &Engine::Impl::relax_trial},
    {Integrator::automatic, "automatic", nullptr, nullptr},
}};

}  // namespace

std::span<const IntegratorEntry> integrators() { return kIntegrators; }

const IntegratorEntry& integrator_entry(Integrator method) {
  for (const IntegratorEntry& e : kIntegrators)
    if (e.method == method) return e;
  throw std::logic_error("an integrator without a row in integrators()");
}

}  // namespace rheodda::core
