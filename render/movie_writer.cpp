#include "render/movie_writer.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <vector>

#include <fmt/format.h>
#include <vtkNew.h>
#include <vtkOggTheoraWriter.h>
#include <vtkPNGReader.h>

#include "engine/types.hpp"

extern char** environ;

namespace drumlab::render {

namespace {

namespace fs = std::filesystem;

fs::path temporary_name(const fs::path& file) {
  fs::path tmp = file;
  tmp.replace_filename(
      fmt::format(".{}.tmp-{}{}", file.stem().string(), ::getpid(), file.extension().string()));
  return tmp;
}

void check_directory(const fs::path& movie) {
  const fs::path dir = movie.has_parent_path() ? movie.parent_path() : fs::path(".");
  if (!fs::is_directory(dir)) {
    throw InputError(
        fmt::format("{}: the directory {} does not exist", movie.string(), dir.string()));
  }
}

void rename_into_place(const fs::path& tmp, const fs::path& file) {
  std::error_code ec;
  fs::rename(tmp, file, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw InputError(fmt::format("{}: cannot rename into place", file.string()));
  }
}

/// Runs ffmpeg without a shell; returns its exit status.
int run_ffmpeg(const fs::path& ffmpeg, const MovieOptions& o, const fs::path& out) {
  const std::vector<std::string> args = {ffmpeg.string(),
                                         "-y",
                                         "-loglevel",
                                         "error",
                                         "-framerate",
                                         std::to_string(o.fps),
                                         "-i",
                                         (o.frames_dir / "frame_%05d.png").string(),
                                         "-c:v",
                                         "libx264",
                                         "-pix_fmt",
                                         "yuv420p",
                                         "-vf",
                                         "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                         out.string()};
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, ffmpeg.c_str(), nullptr, nullptr, argv.data(), environ) != 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

void write_ogv(const MovieOptions& o, const fs::path& out) {
  vtkNew<vtkPNGReader> reader;
  vtkNew<vtkOggTheoraWriter> writer;
  writer->SetInputConnection(reader->GetOutputPort());
  writer->SetFileName(out.c_str());
  writer->SetRate(o.fps);
  writer->SetQuality(2);
  for (std::uint64_t f = 0; f < o.frames; ++f) {
    const fs::path png = o.frames_dir / fmt::format("frame_{:05d}.png", f);
    if (!fs::exists(png)) throw std::runtime_error(fmt::format("{}: missing frame", png.string()));
    reader->SetFileName(png.c_str());
    reader->Update();
    if (f == 0) writer->Start();
    writer->Write();
    if (writer->GetError() != 0) {
      throw std::runtime_error(fmt::format("{}: Theora encoding failed", out.string()));
    }
  }
  writer->End();
}

}  // namespace

fs::path find_program(const std::string& program) {
  if (program.find('/') != std::string::npos) {
    return ::access(program.c_str(), X_OK) == 0 ? fs::path(program) : fs::path();
  }
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path != nullptr ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const fs::path candidate = fs::path(dir.empty() ? "." : dir) / program;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return {};
}

fs::path write_movie(const MovieOptions& o, const fs::path& movie) {
  if (o.frames == 0) throw std::runtime_error("movie: no frames to encode");
  check_directory(movie);
  const fs::path ffmpeg = find_program(o.ffmpeg);
  const fs::path target = ffmpeg.empty() ? fs::path(movie).replace_extension(".ogv") : movie;
  const fs::path tmp = temporary_name(target);
  std::error_code ec;
  try {
    if (!ffmpeg.empty()) {
      const int rc = run_ffmpeg(ffmpeg, o, tmp);
      if (rc != 0 || !fs::exists(tmp) || fs::file_size(tmp) == 0) {
        throw std::runtime_error(
            fmt::format("{}: ffmpeg failed (exit status {})", target.string(), rc));
      }
    } else {
      write_ogv(o, tmp);
      if (!fs::exists(tmp) || fs::file_size(tmp) == 0) {
        throw std::runtime_error(fmt::format("{}: Theora writer wrote nothing", target.string()));
      }
    }
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  rename_into_place(tmp, target);
  return target;
}

}  // namespace drumlab::render
