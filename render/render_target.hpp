#pragma once
// Where a DrumView draws: an OpenGL context (3.2 core or later) that someone else owns. The view
// makes it current before it draws and reads the frame back through it. Two kinds:
//   OffscreenContext (render/offscreen_context.hpp, library drumlab_render_osmesa): OSMesa, no
//     display; the CLI and the headless tests;
//   CurrentGlContext (render/current_gl_context.hpp, library drumlab_render): a context the
//     caller created and made current (GLFW's, a GLX pbuffer, ...); a windowed program.
#include "render/image.hpp"

namespace drumlab::render {

class RenderTarget {
 public:
  virtual ~RenderTarget() = default;
  virtual int width() const = 0;
  virtual int height() const = 0;
  /// Makes the context current on this thread (throws std::runtime_error if it cannot).
  virtual void make_current() = 0;
  /// Waits for OpenGL to finish and reads what the last frame drew (rows top to bottom).
  virtual Image read_image() const = 0;
};

}  // namespace drumlab::render
