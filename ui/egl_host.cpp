#include "ui/egl_host.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace dampbound::ui {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

std::string egl_error() {
  const EGLint e = eglGetError();
  switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    default: {
      char buf[32];
      std::snprintf(buf, sizeof buf, "EGL error 0x%x", static_cast<unsigned>(e));
      return buf;
    }
  }
}

/// True when the space-separated extension list contains `name` as a whole word.
bool has_ext(const char* list, const char* name) {
  if (list == nullptr) return false;
  const size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p != nullptr; p = std::strstr(p + 1, name)) {
    const bool start = p == list || p[-1] == ' ';
    const bool end = p[n] == '\0' || p[n] == ' ';
    if (start && end) return true;
  }
  return false;
}

/// Platform displays are per-process singletons: terminate one only when its last host goes.
std::mutex g_display_mutex;
std::map<EGLDisplay, int> g_display_users;

bool acquire_display(EGLDisplay dpy) {
  std::lock_guard<std::mutex> lock(g_display_mutex);
  EGLint major = 0, minor = 0;
  if (g_display_users[dpy] == 0 && eglInitialize(dpy, &major, &minor) != EGL_TRUE) {
    g_display_users.erase(dpy);
    return false;
  }
  ++g_display_users[dpy];
  return true;
}

void release_display(EGLDisplay dpy) {
  std::lock_guard<std::mutex> lock(g_display_mutex);
  if (--g_display_users[dpy] <= 0) {
    g_display_users.erase(dpy);
    eglTerminate(dpy);
  }
}

}  // namespace

EglPlatform parse_egl_platform(const std::string& name) {
  if (name == "auto") return EglPlatform::Auto;
  if (name == "surfaceless") return EglPlatform::Surfaceless;
  if (name == "device") return EglPlatform::Device;
  throw std::runtime_error("unknown EGL platform '" + name + "' (expected auto, surfaceless or device)");
}

EglOptions default_egl_options() {
  EglOptions o;
  if (const char* env = std::getenv("DAMPBOUND_EGL_PLATFORM"); env != nullptr && *env != '\0') {
    o.platform = parse_egl_platform(env);
  }
  return o;
}

struct EglHost::Impl {
  EGLDisplay dpy = EGL_NO_DISPLAY;
  EGLContext ctx = EGL_NO_CONTEXT;
  EGLSurface pbuffer = EGL_NO_SURFACE;
  std::string platform, renderer, version;
  RenderOptions render;
  RenderStats stats;
  GLuint fbo = 0, rbo = 0;
  int fb_w = 0, fb_h = 0;

  /// Initialises dpy and makes an OpenGL 3.3 core context current on it. Returns "" on
  /// success, else why not (and leaves nothing behind).
  std::string open(EGLDisplay d);
  void close();
  void make_current() const;
  void ensure_fbo(int w, int h);
};

std::string EglHost::Impl::open(EGLDisplay d) {
  if (d == EGL_NO_DISPLAY) return "no display (" + egl_error() + ")";
  if (!acquire_display(d)) return "eglInitialize failed (" + egl_error() + ")";
  dpy = d;
  const char* exts = eglQueryString(dpy, EGL_EXTENSIONS);
  const bool surfaceless = has_ext(exts, "EGL_KHR_surfaceless_context");
  const bool no_config = has_ext(exts, "EGL_KHR_no_config_context") ||
                         has_ext(exts, "EGL_MESA_configless_context");
  auto fail = [&](const std::string& why) {
    close();
    return why;
  };
  if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) return fail("eglBindAPI(OpenGL) failed (" + egl_error() + ")");
  EGLConfig cfg = nullptr;  // EGL_NO_CONFIG_KHR
  if (!surfaceless || !no_config) {
    // Without surfaceless + configless contexts: a config and a tiny pbuffer to be current on.
    const EGLint attrs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                            EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_NONE};
    EGLint n = 0;
    if (eglChooseConfig(dpy, attrs, &cfg, 1, &n) != EGL_TRUE || n < 1) {
      return fail("no OpenGL-renderable EGL config (" + egl_error() + ")");
    }
  }
  const EGLint ctx_attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                              EGL_NONE};
  ctx = eglCreateContext(dpy, cfg, EGL_NO_CONTEXT, ctx_attrs);
  if (ctx == EGL_NO_CONTEXT) return fail("no OpenGL 3.3 core context (" + egl_error() + ")");
  if (!surfaceless) {
    const EGLint pb_attrs[] = {EGL_WIDTH, 16, EGL_HEIGHT, 16, EGL_NONE};
    pbuffer = eglCreatePbufferSurface(dpy, cfg, pb_attrs);
    if (pbuffer == EGL_NO_SURFACE) return fail("no pbuffer surface (" + egl_error() + ")");
  }
  if (eglMakeCurrent(dpy, pbuffer, pbuffer, ctx) != EGL_TRUE) {
    return fail("eglMakeCurrent failed (" + egl_error() + ")");
  }
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor < 33) {
    return fail("context is OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
                ", need 3.3");
  }
  renderer = gl_string(GL_RENDERER);
  version = gl_string(GL_VERSION);
  return "";
}

void EglHost::Impl::close() {
  if (dpy == EGL_NO_DISPLAY) return;
  if (ctx != EGL_NO_CONTEXT) {
    if (eglGetCurrentContext() == ctx) {
      if (fbo != 0) glDeleteFramebuffers(1, &fbo);
      if (rbo != 0) glDeleteRenderbuffers(1, &rbo);
      eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    eglDestroyContext(dpy, ctx);
  }
  if (pbuffer != EGL_NO_SURFACE) eglDestroySurface(dpy, pbuffer);
  release_display(dpy);
  dpy = EGL_NO_DISPLAY;
  ctx = EGL_NO_CONTEXT;
  pbuffer = EGL_NO_SURFACE;
  fbo = rbo = 0;
  fb_w = fb_h = 0;
}

void EglHost::Impl::make_current() const {
  if (eglGetCurrentContext() == ctx) return;
  if (eglMakeCurrent(dpy, pbuffer, pbuffer, ctx) != EGL_TRUE) {
    throw std::runtime_error("EGL: eglMakeCurrent failed (" + egl_error() + ")");
  }
}

void EglHost::Impl::ensure_fbo(int w, int h) {
  if (fbo == 0) {
    glGenFramebuffers(1, &fbo);
    glGenRenderbuffers(1, &rbo);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  if (w != fb_w || h != fb_h) {
    glBindRenderbuffer(GL_RENDERBUFFER, rbo);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rbo);
    fb_w = w;
    fb_h = h;
  }
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    fb_w = fb_h = 0;
    throw std::runtime_error("EGL host: framebuffer " + std::to_string(w) + "x" + std::to_string(h) +
                             " incomplete (status 0x" + std::to_string(status) + ")");
  }
  glReadBuffer(GL_COLOR_ATTACHMENT0);
}

EglHost::EglHost(const EglOptions& options) : impl_(std::make_unique<Impl>()) {
  impl_->render = options.render;
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (client == nullptr || get_display == nullptr || !has_ext(client, "EGL_EXT_platform_base")) {
    throw std::runtime_error("EGL: no platform-display support (EGL_EXT_platform_base missing)");
  }
  std::string why;
  const bool any = options.platform == EglPlatform::Auto;
  if (any || options.platform == EglPlatform::Surfaceless) {
    std::string r = "not supported (EGL_MESA_platform_surfaceless missing)";
    if (has_ext(client, "EGL_MESA_platform_surfaceless")) {
      r = impl_->open(get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
      if (r.empty()) impl_->platform = "surfaceless";
    }
    if (!r.empty()) why += "surfaceless: " + r;
  }
  if (impl_->platform.empty() && (any || options.platform == EglPlatform::Device)) {
    std::string r;
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(
        eglGetProcAddress("eglQueryDevicesEXT"));
    EGLint n = 0;
    if (!has_ext(client, "EGL_EXT_platform_device") || query_devices == nullptr) {
      r = "not supported (EGL_EXT_platform_device missing)";
    } else if (query_devices(0, nullptr, &n) != EGL_TRUE || n <= 0) {
      r = "no EGL devices";
    } else {
      std::vector<EGLDeviceEXT> devices(static_cast<size_t>(n));
      query_devices(n, devices.data(), &n);
      for (EGLint i = 0; i < n && impl_->platform.empty(); ++i) {
        const std::string ri = impl_->open(get_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr));
        if (ri.empty()) {
          impl_->platform = "device " + std::to_string(i);
        } else {
          r += (r.empty() ? "" : ", ") + std::to_string(i) + ": " + ri;
        }
      }
    }
    if (impl_->platform.empty()) why += (why.empty() ? "" : "; ") + std::string("device: ") + r;
  }
  if (impl_->platform.empty()) throw std::runtime_error("EGL: no OpenGL 3.3 context: " + why);
}

EglHost::~EglHost() { impl_->close(); }

Image EglHost::render_frames(int width, int height, const FrameFn& fn, int n_frames) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384) {
    throw std::runtime_error("EGL host: bad image size " + std::to_string(width) + "x" +
                             std::to_string(height));
  }
  impl_->make_current();
  impl_->ensure_fbo(width, height);
  RenderStats stats;
  FrameRenderer renderer(impl_->render);
  FrameInfo info;
  info.width = width;
  info.height = height;
  double rest_ms = 0.0;
  for (int i = 0; i < std::max(n_frames, 1); ++i) {
    const auto t0 = Clock::now();
    info.index = i;
    info.time_s = i / 60.0;
    renderer.frame(info, fn, 1.0f / 60.0f, width, height);
    glFinish();
    const double ms = ms_since(t0);
    if (i == 0) {
      stats.first_frame_ms = ms;
    } else {
      rest_ms += ms;
    }
    ++stats.frames;
    if (info.close) break;
  }
  stats.mean_frame_ms = stats.frames > 1 ? rest_ms / (stats.frames - 1) : stats.first_frame_ms;
  const auto t0 = Clock::now();
  Image img = read_pixels(width, height);
  stats.readback_ms = ms_since(t0);
  impl_->stats = stats;
  return img;
}

const std::string& EglHost::platform_name() const { return impl_->platform; }
const std::string& EglHost::gl_renderer() const { return impl_->renderer; }
const std::string& EglHost::gl_version() const { return impl_->version; }
const RenderStats& EglHost::last_stats() const { return impl_->stats; }

}  // namespace dampbound::ui
