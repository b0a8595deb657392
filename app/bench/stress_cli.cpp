// The stress cases that run the `drumlab` executable as a user does: time steps above the Rayleigh
// time (exit 0 with sane output, or exit 3 with one "unstable:" line, never NaN in a file) and
// adversarial inputs (exit 2 with one line naming the file and key).
#include <cmath>
#include <filesystem>
#include <sstream>

#include <fmt/format.h>

#include "app/bench/stress_process.hpp"
#include "app/bench/stress_scene.hpp"
#include "app/bench/stress_suite.hpp"
#include "engine/drum.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/io/h5_file.hpp"
#include "engine/io/h5_series.hpp"

namespace drumlab::bench {

namespace {

namespace fs = std::filesystem;

std::string first_line(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  return line;
}

/// Positions that are not finite or outside the drum (tolerance 1e-9 R), or "" if all are fine.
std::string check_positions(const std::vector<Vec3>& x, const Drum& drum, const std::string& what) {
  std::size_t bad = 0;
  std::size_t outside = 0;
  for (const Vec3& p : x) {
    if (!p.allFinite()) {
      ++bad;
    } else if (!drum.contains_centre(p, 1e-9 * drum.radius())) {
      ++outside;
    }
  }
  if (bad == 0 && outside == 0) return "";
  return fmt::format("{}: {} non-finite, {} outside; ", what, bad, outside);
}

/// Every file the run left in `dir`: the HDF5 series (all frames) and the checkpoint must hold
/// finite positions inside the drum; no temporary file may be left. Returns problems, "" if none.
std::string check_outputs(const fs::path& dir, const Drum& drum, std::size_t count,
                          std::size_t* frames) {
  std::string problems;
  *frames = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.find(".tmp") != std::string::npos) problems += fmt::format("left {}; ", name);
  }
  if (fs::exists(dir / "series.h5")) {
    h5::Handle f = h5::open_file(dir / "series.h5");
    for (std::size_t k = 0; h5::exists(f.get(), h5_frame_group(k)); ++k) {
      const h5::Handle g = h5::open_group(f.get(), h5_frame_group(k));
      const auto x = h5::read_vec3(g.get(), "position", h5::kAnySize);
      problems += check_positions(x, drum, h5_frame_group(k));
      if (x.size() != count)
        problems += fmt::format("{}: {} particles; ", h5_frame_group(k), x.size());
      ++*frames;
    }
  }
  if (fs::exists(dir / "state.h5")) {
    const Checkpoint c = read_checkpoint(dir / "state.h5");
    problems += check_positions(c.state.particles.position, drum, "checkpoint");
    if (c.state.particles.size() != count)
      problems += fmt::format("checkpoint: {} particles; ", c.state.particles.size());
  }
  return problems;
}

/// A run that may go unstable: `args` (after the scene) run in a fresh folder holding scene.toml
/// (from `s`) and, if given, p.csv. It must exit 0 leaving finite HDF5 frames and a checkpoint
/// inside the drum, or exit 3 with one "unstable:" line, leaving at most files of good states.
StressCase stability_case(const StressContext& ctx, std::string name, const StressScene& s,
                          const std::string& args, const std::string& csv = "") {
  StressCase c;
  c.name = std::move(name);
  c.setup = fmt::format("{}; {}{}--h5 --every 5 --checkpoint --checkpoint-every 10", s.summary(),
                        args, args.empty() ? "" : " ");
  c.expected = "exit 0 and sane files, or exit 3 with one 'unstable:' line; never NaN in a file";
  c.run = [ctx, s, args, csv, name = c.name] {
    const fs::path dir = ctx.work / file_stem(name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    write_text(dir / "scene.toml", s.toml());
    if (!csv.empty()) write_text(dir / "p.csv", csv);
    const ChildResult r =
        run_drumlab(fmt::format("run scene.toml {} --h5 series.h5 --every 5 --checkpoint state.h5 "
                                "--checkpoint-every 10",
                                args),
                    dir);
    std::size_t frames = 0;
    const Drum drum(DrumConfig{s.diameter, s.depth, 0.0, 0.0, DrumEnds::caps, {}});
    std::string problems;
    try {
      problems = check_outputs(dir, drum, s.count, &frames);
    } catch (const std::exception& e) {
      problems = fmt::format("output unreadable: {}", e.what());
    }
    StressOutcome out;
    if (r.exit_code == 0) {
      out.pass = problems.empty() && frames > 0 && fs::exists(dir / "state.h5");
      out.observed = fmt::format("exit 0, stable; {} finite frames + checkpoint inside the drum{}",
                                 frames, problems.empty() ? "" : "; " + problems);
    } else if (r.exit_code == 3) {
      const bool one_line = line_count(r.err) == 1 && r.err.find("unstable:") != std::string::npos;
      out.pass = one_line && problems.empty();
      out.observed = fmt::format(
          "exit 3: \"{}\"; files left: {} HDF5 frames, {}{}", first_line(r.err), frames,
          fs::exists(dir / "state.h5") ? "a finite checkpoint inside the drum" : "no checkpoint",
          problems.empty() ? "" : "; " + problems);
    } else {
      out.observed = fmt::format("exit {}: {}", r.exit_code, first_line(r.err));
    }
    return out;
  };
  return c;
}

/// One adversarial input: `files` are written into a fresh folder, `args` run there; the run must
/// exit with 2 and print exactly one line on stderr containing every string of `tokens`.
struct BadInput {
  std::string name;
  std::string setup;
  std::vector<std::pair<std::string, std::string>> files;  ///< (name, text)
  std::string args;
  std::vector<std::string> tokens;
};

StressCase bad_input_case(const StressContext& ctx, BadInput b) {
  StressCase c;
  c.name = b.name;
  c.setup = b.setup;
  std::string names;
  for (const auto& t : b.tokens) names += fmt::format("{}'{}'", names.empty() ? "" : ", ", t);
  c.expected = fmt::format("exit 2, one line naming {}", names);
  c.run = [ctx, b] {
    const fs::path dir = ctx.work / "inputs" / file_stem(b.name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (const auto& [file, text] : b.files) write_text(dir / file, text);
    const ChildResult r = run_drumlab(b.args, dir);
    bool found = true;
    for (const auto& t : b.tokens) found = found && r.err.find(t) != std::string::npos;
    StressOutcome out;
    out.pass = r.exit_code == 2 && line_count(r.err) == 1 && found;
    out.observed = fmt::format("exit {}: {}", r.exit_code, first_line(r.err));
    if (line_count(r.err) > 1) out.observed += fmt::format(" (+{} lines)", line_count(r.err) - 1);
    return out;
  };
  return c;
}

/// `text` with the line starting with `prefix` replaced by `line` ("" removes it).
std::string with_line(const std::string& text, const std::string& prefix, const std::string& line) {
  std::istringstream in(text);
  std::string out;
  for (std::string l; std::getline(in, l);) {
    if (l.rfind(prefix, 0) == 0) {
      if (!line.empty()) out += line + "\n";
    } else {
      out += l + "\n";
    }
  }
  return out;
}

/// The command line every scene and CSV case runs.
const std::string kBadInputRun = "run scene.toml --steps 1";

/// `drumlab run` on a bad scene.toml: the message names the file, then `tokens`.
BadInput scene_case(std::string name, std::string setup, std::string text,
                    std::vector<std::string> tokens) {
  tokens.insert(tokens.begin(), "scene.toml");
  return BadInput{std::move(name),
                  std::move(setup),
                  {{"scene.toml", std::move(text)}},
                  kBadInputRun,
                  std::move(tokens)};
}

/// `drumlab run` on a file-fill scene whose p.csv is bad: the message names p.csv, then `tokens`.
BadInput csv_case(const std::string& file_scene, std::string name, std::string setup,
                  std::string csv, std::vector<std::string> tokens) {
  tokens.insert(tokens.begin(), "p.csv");
  return BadInput{std::move(name),
                  std::move(setup),
                  {{"scene.toml", file_scene}, {"p.csv", std::move(csv)}},
                  kBadInputRun,
                  std::move(tokens)};
}

/// Bad values, types, keys and syntax in the scene file.
std::vector<BadInput> bad_scene_inputs(const std::string& scene) {
  std::vector<BadInput> v;
  v.push_back(scene_case("scene NaN", "youngs_modulus = nan",
                         with_line(scene, "youngs_modulus", "youngs_modulus = nan"),
                         {"material.youngs_modulus"}));
  v.push_back(scene_case("scene negative radius", "radius = -0.004",
                         with_line(scene, "radius", "radius = -0.004"), {"particles[0].radius"}));
  v.push_back(scene_case("scene empty", "empty file", "", {"missing"}));
  v.push_back(scene_case("scene missing key", "no drum.diameter", with_line(scene, "diameter", ""),
                         {"drum.diameter", "missing"}));
  v.push_back(scene_case("scene wrong type", "diameter = \"big\"",
                         with_line(scene, "diameter", "diameter = \"big\""), {"drum.diameter"}));
  v.push_back(scene_case("scene huge count", "count = 1e9 (integer)",
                         with_line(scene, "count", "count = 1000000000"), {"fill.count"}));
  v.push_back(scene_case("scene TOML syntax", "diameter = = 1",
                         with_line(scene, "diameter", "diameter = = 1"), {"TOML syntax error"}));
  v.push_back(scene_case("scene unknown method", "search = \"m9\"",
                         with_line(scene, "search", "search = \"m9\""), {"search", "m9"}));
  return v;
}

/// Bad options and unwritable outputs on a good scene.
std::vector<BadInput> bad_option_inputs(const std::string& scene) {
  const std::string& run = kBadInputRun;
  std::vector<BadInput> v;
  v.push_back(BadInput{"option unknown method",
                       "--method m9",
                       {{"scene.toml", scene}},
                       run + " --method m9",
                       {"--method", "m9"}});
  v.push_back(BadInput{"dt 2x without --unsafe-dt",
                       "--dt-factor 2",
                       {{"scene.toml", scene}},
                       run + " --dt-factor 2",
                       {"scene.toml", "Rayleigh", "--unsafe-dt"}});
  v.push_back(BadInput{"unwritable --h5",
                       "--h5 missing_dir/x.h5",
                       {{"scene.toml", scene}},
                       run + " --h5 missing_dir/x.h5",
                       {"missing_dir/x.h5"}});
  v.push_back(BadInput{"unwritable --checkpoint",
                       "--checkpoint /proc/drumlab/c.h5",
                       {{"scene.toml", scene}},
                       run + " --checkpoint /proc/drumlab/c.h5",
                       {"--checkpoint", "/proc/drumlab/c.h5"}});
  return v;
}

/// Bad particle files: a missing fill file, bad CSV packings, a bad `contacts --particles` CSV.
std::vector<BadInput> bad_file_inputs(const std::string& file_scene) {
  std::vector<BadInput> v;
  v.push_back(scene_case("fill file missing", "file = \"none.csv\"",
                         with_line(file_scene, "file", "file = \"none.csv\""),
                         {"fill.file", "none.csv"}));
  v.push_back(csv_case(file_scene, "csv NaN", "x = nan", "x,y,z,r\nnan,-0.02,0.01,0.004\n",
                       {":2:", "'x'"}));
  v.push_back(csv_case(file_scene, "csv negative radius", "r = -0.004",
                       "x,y,z,r\n0,-0.02,0.01,-0.004\n", {":2:", "'r'"}));
  v.push_back(csv_case(file_scene, "csv empty", "empty file", "", {"empty"}));
  v.push_back(
      csv_case(file_scene, "csv header only", "x,y,z,r only", "x,y,z,r\n", {"no particles"}));
  v.push_back(csv_case(file_scene, "csv missing column", "x,y,r", "x,y,r\n0,0,0.004\n", {"'z'"}));
  v.push_back(csv_case(file_scene, "csv huge coordinates", "x = 1e300",
                       "x,y,z,r\n0,-0.02,0.01,0.004\n1e300,-0.02,0.01,0.004\n",
                       {":3:", "outside the drum"}));
  v.push_back(csv_case(file_scene, "csv foreign radius", "r = 0.005 (class 0.004)",
                       "x,y,z,r\n0,-0.02,0.01,0.005\n", {":2:", "radii"}));
  v.push_back(csv_case(file_scene, "csv partial velocity", "x,y,z,r,vx",
                       "x,y,z,r,vx\n0,-0.02,0.01,0.004,1\n", {"vx, vy, vz"}));
  v.push_back(csv_case(file_scene, "overlap 30% refused", "two particles 0.3 r apart from touching",
                       "x,y,z,r\n0,-0.02,0.0125,0.004\n0.0068,-0.02,0.0125,0.004\n",
                       {":3:", "line 2", "overlaps"}));
  v.push_back(BadInput{"contacts csv NaN",
                       "contacts --particles (y = nan)",
                       {{"p.csv", "x,y,z,r\n0,nan,0,0.004\n"}},
                       "contacts --particles p.csv --method m5",
                       {"p.csv:2:", "'y'"}});
  return v;
}

std::vector<BadInput> bad_inputs() {
  StressScene s;
  StressScene f = s;
  f.fill_file = "p.csv";
  std::vector<BadInput> v = bad_scene_inputs(s.toml());
  for (BadInput& b : bad_option_inputs(s.toml())) v.push_back(std::move(b));
  for (BadInput& b : bad_file_inputs(f.toml())) v.push_back(std::move(b));
  return v;
}

}  // namespace

std::vector<StressCase> cli_stress_cases(const StressContext& ctx) {
  std::vector<StressCase> cases;
  StressScene s;
  s.count = 200;
  s.settle_time = 0.02;
  s.duration = ctx.quick ? 0.03 : 0.1;
  s.diagnostics_every = 20;
  for (const double f : {1.0, 2.0, 5.0}) {
    cases.push_back(stability_case(ctx, fmt::format("dt = {:g} x Rayleigh", f), s,
                                   fmt::format("--unsafe-dt --dt-factor {:g}", f)));
  }
  StressScene v = s;
  v.fill_file = "p.csv";
  cases.push_back(stability_case(ctx, "csv 1000 m/s particle", v, "",
                                 "x,y,z,r,vx,vy,vz\n0,-0.02,0.0125,0.004,1000,0,0\n"
                                 "0.012,-0.02,0.0125,0.004,0,0,0\n"));
  for (BadInput& b : bad_inputs()) cases.push_back(bad_input_case(ctx, std::move(b)));
  return cases;
}

}  // namespace drumlab::bench
