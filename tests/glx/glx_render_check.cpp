// The scene without OSMesa: DrumView drawing into a GLX context this program creates and owns (a
// pbuffer on an X server; ctest runs it under xvfb-run), through render::CurrentGlContext, the
// way the GUI draws into GLFW's context. Linked with drumlab_render alone: no libOSMesa, no
// app/cli/osmesa_glx_shim.cpp. Exit 0: the frame shows the bed and the focus colours; 77: no X
// server (skipped); 1: failure.
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "engine/scene/scene_config.hpp"
#include "engine/session/run_session.hpp"
#include "render/current_gl_context.hpp"
#include "render/drum_view.hpp"
#include "render/frame_writer.hpp"
#include "render/grid_overlay.hpp"

// X11 and GLX last: their macros (None, Bool, Status, ...) would break Eigen.
// clang-format off
#include <X11/Xlib.h>
#include <GL/glx.h>
// clang-format on

namespace {

using CreateContextAttribs = GLXContext (*)(Display*, GLXFBConfig, GLXContext, Bool, const int*);

int distance(const drumlab::render::Image& img, int x, int y, const double* rgb) {
  const auto px = img.pixel(x, y);
  int d = 0;
  for (int c = 0; c < 3; ++c)
    d = std::max(d, std::abs(px[c] - static_cast<int>(255.0 * rgb[c] + 0.5)));
  return d;
}

std::size_t pixels_near(const drumlab::render::Image& img, const double* rgb, int tolerance) {
  std::size_t n = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) n += distance(img, x, y, rgb) <= tolerance;
  }
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace drumlab;
  Display* display = XOpenDisplay(nullptr);
  if (display == nullptr) {
    std::puts("SKIPPED: no X server (run under xvfb-run)");
    return 77;
  }
  constexpr int kW = 480, kH = 360;
  const int fb_attribs[] = {GLX_DRAWABLE_TYPE,
                            GLX_PBUFFER_BIT,
                            GLX_RENDER_TYPE,
                            GLX_RGBA_BIT,
                            GLX_RED_SIZE,
                            8,
                            GLX_GREEN_SIZE,
                            8,
                            GLX_BLUE_SIZE,
                            8,
                            GLX_ALPHA_SIZE,
                            8,
                            GLX_DEPTH_SIZE,
                            24,
                            GLX_STENCIL_SIZE,
                            8,
                            GLX_DOUBLEBUFFER,
                            True,
                            None};
  int count = 0;
  GLXFBConfig* configs = glXChooseFBConfig(display, DefaultScreen(display), fb_attribs, &count);
  if (configs == nullptr || count == 0) {
    std::puts("FAILED: no GLX framebuffer configuration with a pbuffer");
    return 1;
  }
  const auto create = reinterpret_cast<CreateContextAttribs>(
      glXGetProcAddressARB(reinterpret_cast<const GLubyte*>("glXCreateContextAttribsARB")));
  const int ctx_attribs[] = {GLX_CONTEXT_MAJOR_VERSION_ARB,
                             3,
                             GLX_CONTEXT_MINOR_VERSION_ARB,
                             2,
                             GLX_CONTEXT_PROFILE_MASK_ARB,
                             GLX_CONTEXT_CORE_PROFILE_BIT_ARB,
                             None};
  GLXContext context =
      create != nullptr ? create(display, configs[0], nullptr, True, ctx_attribs) : nullptr;
  const int pb_attribs[] = {GLX_PBUFFER_WIDTH, kW, GLX_PBUFFER_HEIGHT, kH, None};
  GLXPbuffer pbuffer = glXCreatePbuffer(display, configs[0], pb_attribs);
  XFree(configs);
  if (context == nullptr || !glXMakeContextCurrent(display, pbuffer, pbuffer, context)) {
    std::puts("FAILED: could not create or bind a GLX 3.2 core context");
    return 1;
  }
  int status = 1;
  try {
    const SceneConfig scene = load_scene(std::string(DRUMLAB_SCENES_DIR) + "/teach_stencil.toml");
    SessionOptions options;
    options.method = "m2";  // a cell grid: the focus has an own cell (a Verlet list draws none)
    RunSession session(scene, options);
    session.settle();
    const auto sim = session.release_simulation();
    render::CurrentGlContext target(kW, kH, [&] {
      if (!glXMakeContextCurrent(display, pbuffer, pbuffer, context)) std::abort();
    });
    render::ViewOptions view_options;
    view_options.width = kW;
    view_options.height = kH;
    view_options.grid = true;
    view_options.focus_id = render::auto_focus_id(sim->particles());
    std::size_t own = 0, contacts = 0;
    {
      render::DrumView view(view_options, target);
      const render::Image img = view.render(*sim);
      if (argc > 1) render::write_png(img, argv[1]);
      own = pixels_near(img, render::kOwnCellColor, 30);
      contacts = pixels_near(img, render::kContactColor, 30);
    }
    std::printf("GLX frame %dx%d: %zu own-cell pixels, %zu contact pixels (%s)\n", kW, kH, own,
                contacts, reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
    status = own > 0 && contacts > 0 ? 0 : 1;
    if (status != 0) std::puts("FAILED: the focus colours are missing from the GLX frame");
  } catch (const std::exception& e) {
    std::printf("FAILED: %s\n", e.what());
  }
  glXMakeContextCurrent(display, None, None, nullptr);
  glXDestroyPbuffer(display, pbuffer);
  glXDestroyContext(display, context);
  XCloseDisplay(display);
  return status;
}
