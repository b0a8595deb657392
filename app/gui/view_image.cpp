#include "app/gui/view_image.hpp"

#include <stdexcept>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

namespace drumlab::gui {

ViewImage::~ViewImage() {
  release();
}

void ViewImage::release() {
  if (framebuffer_ != 0) glDeleteFramebuffers(1, &framebuffer_);
  if (texture_ != 0) glDeleteTextures(1, &texture_);
  if (depth_ != 0) glDeleteRenderbuffers(1, &depth_);
  framebuffer_ = texture_ = depth_ = 0;
  width_ = height_ = 0;
}

void ViewImage::resize(int width, int height) {
  if (width == width_ && height == height_ && framebuffer_ != 0) return;
  if (width <= 0 || height <= 0) throw std::runtime_error("ViewImage: size must be positive");
  if (framebuffer_ == 0) {
    glGenFramebuffers(1, &framebuffer_);
    glGenTextures(1, &texture_);
    glGenRenderbuffers(1, &depth_);
  }
  width_ = width;
  height_ = height;
  glBindTexture(GL_TEXTURE_2D, texture_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_, 0);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error("ViewImage: the view's framebuffer object is incomplete");
  }
}

void ViewImage::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
}

void ViewImage::bind_window() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void ViewImage::show(int x, int y, int width, int height) const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  const GLenum filter = width == width_ && height == height_ ? GL_NEAREST : GL_LINEAR;
  glBlitFramebuffer(0, 0, width_, height_, x, y, x + width, y + height, GL_COLOR_BUFFER_BIT,
                    filter);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace drumlab::gui
