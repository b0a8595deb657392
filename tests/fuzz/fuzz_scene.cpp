// libFuzzer harness: a scene file's text through the loader and the full validation
// (parse_scene). Bad input must be an InputError; anything else (another exception, a crash, a
// sanitizer report) is a finding, and so is a scene accepted with a non-finite number in it.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "engine/scene/scene_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  drumlab::SceneConfig s;
  try {
    s = drumlab::parse_scene(text, "fuzz.toml");
  } catch (const drumlab::InputError&) {
    return 0;  // refused with its one line: the expected outcome for most inputs
  }
  // Accepted: no silent NaN or infinity in what the engine will use.
  const auto finite = [](double v) { return std::isfinite(v); };
  bool ok = finite(s.drum.diameter) && finite(s.drum.depth) && finite(s.drum.omega) &&
            s.gravity.allFinite() && finite(s.material.density) &&
            finite(s.material.youngs_modulus) && finite(s.material.friction);
  for (const auto& c : s.classes) ok = ok && finite(c.radius) && c.radius > 0.0;
  if (!ok) std::abort();
  return 0;
}
