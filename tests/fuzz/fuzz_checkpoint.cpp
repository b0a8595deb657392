// libFuzzer harness: the bytes as a checkpoint file, through the paths a restart takes: the
// CLI's (RunSession: read, checked against the scene, a Simulation built) for the dry scene of
// tests/fuzz/scenes/ (or its wet twin when the file is wet), and an MPI rank's share (the middle
// third of the rows, read_checkpoint_rows). Bad input must be an InputError; an accepted state is
// stepped twice and must then be finite or stop as UnstableError. Anything else (another
// exception, a crash, a sanitizer report, a NaN in an accepted run) is a finding.
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "engine/io/checkpoint.hpp"
#include "engine/session/run_session.hpp"
#include "tests/fuzz/restart_and_step.hpp"
#include "tests/fuzz/scratch_file.hpp"

namespace {

namespace fs = std::filesystem;

const drumlab::SceneConfig& scene(bool wet) {
  static const drumlab::SceneConfig dry = drumlab::load_scene(DRUMLAB_FUZZ_SCENES "/dry.toml");
  static const drumlab::SceneConfig wet_scene =
      drumlab::load_scene(DRUMLAB_FUZZ_SCENES "/wet.toml");
  return wet ? wet_scene : dry;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const drumlab::fuzz::ScratchFile scratch("drumlab-fuzz-checkpoint");
  const fs::path& file = scratch.path();
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    drumlab::fuzz::restart_and_step(scene(false), file);
  } catch (const drumlab::InputError& e) {
    // A wet checkpoint is refused by the dry scene ("a dry and a wet scene do not mix"): the
    // wet scene takes it through the same path.
    if (std::string(e.what()).find("do not mix") != std::string::npos) {
      try {
        drumlab::fuzz::restart_and_step(scene(true), file);
      } catch (const drumlab::InputError&) {
      }
    }
  }
  try {  // an MPI rank's share: rows [n/3, 2n/3)
    const std::size_t n = drumlab::read_checkpoint_rows(file, 0, 0).particles;
    drumlab::read_checkpoint_rows(file, n / 3, n / 3);
  } catch (const drumlab::InputError&) {
  }
  return 0;
}
