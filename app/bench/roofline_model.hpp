#pragma once
// The work of one DEM step, counted from the code: floating-point operations, divisions and
// square roots, and bytes, per unit of work the engine counts (StepWork: a listed pair, a touching
// contact, a wall candidate, an integrated particle, a re-ordering). `drumlab bench roofline`
// multiplies these costs by the counts of a run and sets them against the machine's limits
// (machine_limits.hpp).
//
// How the costs were counted (engine/contact/contact_kernel.hpp, hertz_mindlin.hpp,
// rolling_resistance.hpp, liquid_bridge.hpp, engine/simulation.cpp): every add, subtract and
// multiply is one flop, a fused multiply-add two; divisions and square roots are counted apart
// (`divsqrt`), because they run on a slower unit; compares, selects, abs and min/max are not
// counted. Bytes: `stream` is what a phase reads and writes once per unit from arrays it walks in
// order (they come from the level of the memory hierarchy that holds the phase's working set);
// `gather` is what it reads at scattered places (a partner's position, velocity, spin), which the
// Morton order of the particles keeps mostly in L1/L2. A model: each count is stated next to its
// line of code, and the totals are good to about 10 %, not to the flop.
#include <cstddef>

#include "engine/simulation.hpp"

namespace drumlab::bench {

struct Work {
  double flops = 0.0;    ///< add, sub, mul (FMA = 2)
  double divsqrt = 0.0;  ///< divisions and square roots
  double stream = 0.0;   ///< bytes read and written in order
  double gather = 0.0;   ///< bytes read at scattered places

  Work& operator+=(const Work& o) {
    flops += o.flops;
    divsqrt += o.divsqrt;
    stream += o.stream;
    gather += o.gather;
    return *this;
  }
  Work operator+(const Work& o) const {
    Work w = *this;
    return w += o;
  }
  Work operator*(double k) const { return {flops * k, divsqrt * k, stream * k, gather * k}; }
};

/// What the scene's law computes (ContactModel's choices, made once per run).
struct LawShape {
  bool hertz = true;            ///< pair normal law: Hertz (else the linear spring-dashpot)
  bool wall_hertz = true;       ///< the same for wall contacts
  bool tangential = true;       ///< pair tangential spring with history
  bool rolling = false;         ///< pair rolling resistance
  bool wall_tangential = true;  ///< wall tangential spring with history
  bool wall_rolling = false;
  bool rotation = true;            ///< spins integrated
  bool cohesive = false;           ///< liquid bridges or adhesion: the cohesive pass
  std::size_t particle_bytes = 0;  ///< bytes of one particle in all its arrays (for_each_array)
};

/// The law of `scene` as the engine composes it, and the bytes of a particle of `particles`.
LawShape law_shape(const SceneConfig& scene, const Particles& particles);

/// Unit costs.
Work listed_pair_cost();                           ///< the distance test of a listed pair
Work touching_pair_cost(const LawShape& s);        ///< the contact kernel and the force scatter
Work cohesive_pair_cost();                         ///< a live bridge's force (cohesive pass)
Work wall_candidate_cost();                        ///< the drum geometry of a wall candidate
Work wall_contact_cost(const LawShape& s);         ///< the contact kernel on a wall contact
Work integrated_particle_cost(const LawShape& s);  ///< both half kicks and the drift
Work reordered_particle_cost(const LawShape& s);   ///< Morton key, sort share, permutation
Work tested_pair_cost();       ///< a distance test in a search or a Verlet rebuild (candidates)
Work binned_particle_cost();   ///< putting a particle into a search grid
Work patched_particle_cost();  ///< a Verlet list patch's scan and grid, per particle

/// Per phase of a run, the work done; the counts come from PhaseStats (and samples of the live
/// bridges, which the engine does not sum per step).
struct PhaseWork {
  Work search, forces, walls, integration, reorder;
  double working_set_forces = 0.0;     ///< bytes the pair loop touches in one step
  double working_set_particles = 0.0;  ///< bytes of all particle arrays
};

struct RunCounts {
  StepWork work;  ///< summed over the timed steps (wall contacts included)
  std::uint64_t steps = 0;
  std::uint64_t pairs_tested = 0;  ///< search distance tests, summed (SearchCounters)
  std::uint64_t builds = 0;        ///< search structure builds (each step for a grid; rebuilds)
  std::uint64_t patches = 0;       ///< Verlet list patches (the moved particles' pairs replaced)
  bool verlet = false;             ///< the method keeps a Verlet list
  double cohesive_pairs_per_step = 0.0;  ///< live bridges, sampled
};

PhaseWork phase_work(const LawShape& s, const RunCounts& c);

}  // namespace drumlab::bench
