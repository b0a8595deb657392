#pragma once
// The restart path of the checkpoint harnesses (fuzz_checkpoint.cpp, fuzz_checkpoint_values.cpp):
// `drumlab run SCENE --restart FILE` as the CLI starts it, stepped twice. A refusal is an
// InputError (left to the caller); a run that stops as UnstableError is fine; an accepted state
// must step to finite positions and a finite liquid total, else abort (a finding).
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "engine/session/run_session.hpp"

namespace drumlab::fuzz {

inline void restart_and_step(const SceneConfig& scene, const std::filesystem::path& file) {
  SessionOptions o;
  o.restart = file.string();
  RunSession session(scene, o);
  Simulation& sim = session.simulation();
  try {
    sim.advance(2);
  } catch (const UnstableError&) {
    return;
  }
  for (const Vec3& x : sim.particles().position) {
    if (!x.allFinite()) std::abort();  // a silent NaN from an accepted checkpoint
  }
  if (!std::isfinite(sim.liquid().total())) std::abort();
}

}  // namespace drumlab::fuzz
