// GLX entry points for HEADLESS executables only (the drumlab CLI and the tests), never a
// GUI. Debian's VTK 9.1 is built for GLX: its GLEW (glewInit -> glxewInit) loads OpenGL functions
// through glXGetProcAddressARB, asks glXGetCurrentDisplay for a display, then calls
// glXQueryVersion and glXGetClientString on it. These definitions in the executable take precedence
// over libGLX's: OpenGL functions come from OSMesa (whose context render/offscreen_context.cpp
// makes current), and the GLX queries answer "GLX 1.2, no extensions" for a placeholder display
// that is non-null while an OSMesa context is current. See render/README.md, section "Rendering
// without a display".
#include <cstring>

#include <GL/osmesa.h>

namespace {
int placeholder_display = 0;  // stands for a "Display*"; never dereferenced
}

extern "C" {

using GlxProc = void (*)();

void* glXGetCurrentDisplay() {
  return OSMesaGetCurrentContext() != nullptr ? static_cast<void*>(&placeholder_display) : nullptr;
}

int glXQueryVersion(void* /*display*/, int* major, int* minor) {
  if (major != nullptr) *major = 1;
  if (minor != nullptr) *minor = 2;
  return 1;
}

const char* glXGetClientString(void* /*display*/, int /*name*/) {
  return "";
}

GlxProc glXGetProcAddressARB(const unsigned char* name) {
  const char* n = reinterpret_cast<const char*>(name);
  if (std::strcmp(n, "glXGetCurrentDisplay") == 0) {
    return reinterpret_cast<GlxProc>(&glXGetCurrentDisplay);
  }
  if (std::strcmp(n, "glXQueryVersion") == 0) return reinterpret_cast<GlxProc>(&glXQueryVersion);
  if (std::strcmp(n, "glXGetClientString") == 0) {
    return reinterpret_cast<GlxProc>(&glXGetClientString);
  }
  if (std::strncmp(n, "glX", 3) == 0) return nullptr;  // no other GLX behind this context
  return reinterpret_cast<GlxProc>(OSMesaGetProcAddress(n));
}

GlxProc glXGetProcAddress(const unsigned char* name) {
  return glXGetProcAddressARB(name);
}

}  // extern "C"
