#include "ui/mesh_renderer.hpp"

#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ui/mesh_style.hpp"

namespace dampbound::ui {

namespace {

const char* const kVertex = R"(#version 330 core
layout(location = 0) in vec3 pos;
layout(location = 1) in vec4 color;
uniform mat4 mvp;
uniform float point_size;
uniform vec4 tint;
uniform int use_tint;
out vec4 v_color;
void main() {
  gl_Position = mvp * vec4(pos, 1.0);
  gl_PointSize = point_size;
  v_color = use_tint == 1 ? tint : color;
}
)";

const char* const kFragment = R"(#version 330 core
in vec4 v_color;
uniform int round_points;
uniform float point_alpha;
out vec4 frag;
void main() {
  if (round_points == 1) {
    vec2 d = gl_PointCoord * 2.0 - 1.0;
    float r = dot(d, d);
    if (r > 1.0) discard;
    frag = vec4(v_color.rgb * (1.0 - 0.35 * r), v_color.a * point_alpha);  // a shaded bead
  } else {
    frag = v_color;
  }
}
)";

GLuint compile(GLenum type, const char* src) {
  const GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (ok == 0) {
    char log[1024] = {0};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    std::fprintf(stderr, "dampbound: warning: mesh shader: %s\n", log);
    glDeleteShader(s);
    return 0;
  }
  return s;
}

void set_color(std::uint8_t* out, ImU32 c) {
  out[0] = static_cast<std::uint8_t>(c & 0xFF);
  out[1] = static_cast<std::uint8_t>((c >> 8) & 0xFF);
  out[2] = static_cast<std::uint8_t>((c >> 16) & 0xFF);
  out[3] = static_cast<std::uint8_t>((c >> 24) & 0xFF);
}

GLsizeiptr bytes(size_t n) {
  return static_cast<GLsizeiptr>(n);
}

/// The GL state render() changes, put back afterwards.
struct SavedState {
  GLint draw_fbo = 0, read_fbo = 0, program = 0, vao = 0, array_buffer = 0;
  GLint viewport[4] = {0, 0, 0, 0};
  GLboolean depth = GL_FALSE, blend = GL_FALSE, scissor = GL_FALSE, cull = GL_FALSE;
  SavedState() {
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_fbo);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_fbo);
    glGetIntegerv(GL_CURRENT_PROGRAM, &program);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao);
    glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &array_buffer);
    glGetIntegerv(GL_VIEWPORT, viewport);
    depth = glIsEnabled(GL_DEPTH_TEST);
    blend = glIsEnabled(GL_BLEND);
    scissor = glIsEnabled(GL_SCISSOR_TEST);
    cull = glIsEnabled(GL_CULL_FACE);
  }
  ~SavedState() {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw_fbo));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read_fbo));
    glUseProgram(static_cast<GLuint>(program));
    glBindVertexArray(static_cast<GLuint>(vao));
    glBindBuffer(GL_ARRAY_BUFFER, static_cast<GLuint>(array_buffer));
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    auto set = [](GLenum cap, GLboolean on) { on ? glEnable(cap) : glDisable(cap); };
    set(GL_DEPTH_TEST, depth);
    set(GL_BLEND, blend);
    set(GL_SCISSOR_TEST, scissor);
    set(GL_CULL_FACE, cull);
    glDisable(GL_PROGRAM_POINT_SIZE);
  }
};

void setup_vao(GLuint vao, GLuint pos, GLuint col) {
  glBindVertexArray(vao);
  glBindBuffer(GL_ARRAY_BUFFER, pos);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, col);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 4, GL_UNSIGNED_BYTE, GL_TRUE, 0, nullptr);
}

}  // namespace

bool MeshRenderer::init() {
  const GLuint vs = compile(GL_VERTEX_SHADER, kVertex);
  const GLuint fs = compile(GL_FRAGMENT_SHADER, kFragment);
  if (vs == 0 || fs == 0) return false;
  program_ = glCreateProgram();
  glAttachShader(program_, vs);
  glAttachShader(program_, fs);
  glLinkProgram(program_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (ok == 0) return false;
  loc_mvp_ = glGetUniformLocation(program_, "mvp");
  loc_point_size_ = glGetUniformLocation(program_, "point_size");
  loc_tint_ = glGetUniformLocation(program_, "tint");
  loc_use_tint_ = glGetUniformLocation(program_, "use_tint");
  loc_round_ = glGetUniformLocation(program_, "round_points");
  loc_point_alpha_ = glGetUniformLocation(program_, "point_alpha");
  GLuint b[5];
  glGenBuffers(5, b);
  vbo_pos_ = b[0], vbo_col_ = b[1], ebo_ = b[2], vbo_anchor_ = b[3], vbo_anchor_col_ = b[4];
  glGenVertexArrays(1, &vao_);
  glGenVertexArrays(1, &anchor_vao_);
  setup_vao(vao_, vbo_pos_, vbo_col_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);  // part of vao_'s state
  setup_vao(anchor_vao_, vbo_anchor_, vbo_anchor_col_);
  glBindVertexArray(0);
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples_);
  glGenFramebuffers(1, &fbo_ms_);
  glGenFramebuffers(1, &fbo_tex_);
  glGenRenderbuffers(1, &rb_color_);
  glGenRenderbuffers(1, &rb_depth_);
  glGenTextures(1, &tex_);
  return glGetError() == GL_NO_ERROR;
}

void MeshRenderer::resize(int width, int height, int samples) {
  samples = std::clamp(samples, 1, std::max(max_samples_, 1));
  if (width == width_ && height == height_ && samples == samples_) return;
  width_ = width;
  height_ = height;
  samples_ = samples;
  glBindTexture(GL_TEXTURE_2D, tex_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_tex_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex_, 0);
  // One sample: draw straight into the texture. More: a multisampled target, resolved by a blit.
  const GLsizei ms = samples_ > 1 ? samples_ : 0;
  glBindRenderbuffer(GL_RENDERBUFFER, rb_depth_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, ms, GL_DEPTH_COMPONENT24, width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_ms_);
  if (samples_ > 1) {
    glBindRenderbuffer(GL_RENDERBUFFER, rb_color_);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, ms, GL_RGBA8, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb_color_);
  } else {
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex_, 0);
  }
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb_depth_);
}

void MeshRenderer::upload(const MeshDrawData& d) {
  const Model& m = *d.model;
  const std::vector<Vec3>& x = *d.x;
  const size_t n = std::min(x.size(), m.spec().rest.size());
  pos_.resize(3 * n);
  col_.resize(4 * n);
  for (size_t i = 0; i < n; ++i) {
    const bool ok = x[i].allFinite();
    const Vec3& p = ok ? x[i] : m.spec().rest[i];  // a non-finite node is hidden, never sent to GL
    for (int k = 0; k < 3; ++k) pos_[3 * i + static_cast<size_t>(k)] = static_cast<float>(p[k]);
    const NodeStatus s = i < d.status->size() ? (*d.status)[i] : NodeStatus::within;
    const bool unguaranteed = d.safe_bound && i < d.safe_bound->size() &&
                              m.lower_bound[i] > (*d.safe_bound)[i];
    const bool shaded = d.shade && d.shade->size() == n;
    set_color(&col_[4 * i], !ok     ? IM_COL32(0, 0, 0, 0)
                            : shaded ? shade_color((*d.shade)[i])
                                     : node_color(s, unguaranteed));
  }
  node_count_ = static_cast<int>(n);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_pos_);
  glBufferData(GL_ARRAY_BUFFER, bytes(pos_.size() * sizeof(float)), pos_.data(), GL_STREAM_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_col_);
  glBufferData(GL_ARRAY_BUFFER, bytes(col_.size()), col_.data(), GL_STREAM_DRAW);
  if (d.topology != topology_ || d.model != model_) {  // springs changed: new index buffer
    std::vector<std::uint32_t> idx;
    idx.reserve(2 * m.spec().springs.size());
    for (const Spring& s : m.spec().springs) {
      if (static_cast<size_t>(s.i) >= n || static_cast<size_t>(s.j) >= n) continue;
      idx.push_back(static_cast<std::uint32_t>(s.i));
      idx.push_back(static_cast<std::uint32_t>(s.j));
    }
    glBindVertexArray(vao_);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, bytes(idx.size() * sizeof(std::uint32_t)), idx.data(),
                 GL_STATIC_DRAW);
    index_count_ = static_cast<int>(idx.size());
    topology_ = d.topology;
    model_ = d.model;
  }
  anchor_vertices_ = 0;
  if (d.anchors) {
    anchor_pos_.clear();
    anchor_col_.clear();
    for (size_t i = 0; i < n && i < m.spec().anchor_scale.size(); ++i) {
      if (m.spec().anchor_scale[i] <= 0 || !x[i].allFinite()) continue;
      for (const Vec3* p : {&x[i], &m.spec().rest[i]})
        for (int k = 0; k < 3; ++k) anchor_pos_.push_back(static_cast<float>((*p)[k]));
      for (int v = 0; v < 2; ++v) {
        anchor_col_.resize(anchor_col_.size() + 4);
        set_color(&anchor_col_[anchor_col_.size() - 4], IM_COL32(200, 160, 90, v == 0 ? 180 : 40));
      }
      anchor_vertices_ += 2;
    }
    glBindBuffer(GL_ARRAY_BUFFER, vbo_anchor_);
    glBufferData(GL_ARRAY_BUFFER, bytes(anchor_pos_.size() * sizeof(float)), anchor_pos_.data(),
                 GL_STREAM_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, vbo_anchor_col_);
    glBufferData(GL_ARRAY_BUFFER, bytes(anchor_col_.size()), anchor_col_.data(), GL_STREAM_DRAW);
  }
}

unsigned MeshRenderer::render(const MeshDrawData& d, int width, int height) {
  if (failed_ || d.model == nullptr || d.x == nullptr || d.status == nullptr) return 0;
  width = std::max(width, 1);
  height = std::max(height, 1);
  const SavedState saved;
  if (!ready_) {
    ready_ = init();
    failed_ = !ready_;
    if (failed_) {
      std::fprintf(stderr, "dampbound: warning: the mesh view cannot use OpenGL 3.3; not drawn\n");
      return 0;
    }
  }
  glBindVertexArray(0);
  resize(width, height, d.samples);
  upload(d);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_ms_);
  glViewport(0, 0, width, height);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_CULL_FACE);
  glClearColor(d.background[0], d.background[1], d.background[2], d.background[3]);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glEnable(GL_PROGRAM_POINT_SIZE);
  glUseProgram(program_);
  glUniformMatrix4fv(loc_mvp_, 1, GL_FALSE, d.view_proj.data());
  glUniform1f(loc_point_size_, d.point_size);
  glUniform1i(loc_round_, 0);
  if (d.anchors && anchor_vertices_ > 0) {
    glUniform1i(loc_use_tint_, 0);
    glBindVertexArray(anchor_vao_);
    glDrawArrays(GL_LINES, 0, anchor_vertices_);
  }
  glBindVertexArray(vao_);
  if (d.springs && index_count_ > 0) {
    const ImU32 c = spring_color();
    glUniform1i(loc_use_tint_, 1);
    glUniform4f(loc_tint_, static_cast<float>(c & 0xFF) / 255.0f,
                static_cast<float>((c >> 8) & 0xFF) / 255.0f,
                static_cast<float>((c >> 16) & 0xFF) / 255.0f,
                static_cast<float>((c >> 24) & 0xFF) / 255.0f * d.spring_alpha);
    glDrawElements(GL_LINES, index_count_, GL_UNSIGNED_INT, nullptr);
  }
  glUniform1i(loc_use_tint_, 0);
  glUniform1i(loc_round_, 1);
  glUniform1f(loc_point_alpha_, d.point_alpha);
  glDrawArrays(GL_POINTS, 0, node_count_);
  if (samples_ > 1) {  // resolve the multisampled image into the texture ImGui shows
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_ms_);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo_tex_);
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }
  return tex_;
}

void MeshRenderer::release() {
  if (!ready_) return;
  glDeleteProgram(program_);
  const GLuint b[5] = {vbo_pos_, vbo_col_, ebo_, vbo_anchor_, vbo_anchor_col_};
  glDeleteBuffers(5, b);
  glDeleteVertexArrays(1, &vao_);
  glDeleteVertexArrays(1, &anchor_vao_);
  glDeleteFramebuffers(1, &fbo_ms_);
  glDeleteFramebuffers(1, &fbo_tex_);
  glDeleteRenderbuffers(1, &rb_color_);
  glDeleteRenderbuffers(1, &rb_depth_);
  glDeleteTextures(1, &tex_);
  ready_ = false;
  width_ = height_ = 0;
  topology_ = 0;
  model_ = nullptr;
}

}  // namespace dampbound::ui
