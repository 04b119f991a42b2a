// The window backend: a GLFW window with an OpenGL 3.3 core context.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "render/gl_context.h"

namespace tetlod::render {
namespace {

void* glfw_get_proc(const char* name) {
  return reinterpret_cast<void*>(glfwGetProcAddress(name));
}

std::string last_glfw_error() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description ? description : "unknown GLFW error";
}

class GlfwContext : public WindowContext {
 public:
  ~GlfwContext() override {
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
  }
  const GlApi& gl() const override { return gl_; }
  std::string description() const override { return description_; }
  bool make_current() override {
    glfwMakeContextCurrent(window_);
    return true;
  }
  void* native_window() const override { return window_; }
  bool should_close() const override { return glfwWindowShouldClose(window_); }
  void swap_buffers() override { glfwSwapBuffers(window_); }
  void poll_events() override { glfwPollEvents(); }
  void framebuffer_size(int* width, int* height) const override {
    glfwGetFramebufferSize(window_, width, height);
  }

  bool init(int width, int height, const std::string& title, bool visible, std::string* error) {
    if (!glfwInit()) {
      *error = "no window: GLFW could not start (" + last_glfw_error() + ")";
      return false;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
      *error = "no window: no OpenGL 3.3 core context (" + last_glfw_error() + ")";
      return false;
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(1);
    if (!load_gl_api(&glfw_get_proc, &gl_, error)) return false;
    description_ = std::string("GLFW: ") +
                   reinterpret_cast<const char*>(gl_.GetString(GL_RENDERER)) + ", " +
                   reinterpret_cast<const char*>(gl_.GetString(GL_VERSION));
    return true;
  }

 private:
  GLFWwindow* window_ = nullptr;
  GlApi gl_;
  std::string description_;
};

}  // namespace

std::unique_ptr<WindowContext> WindowContext::create(int width, int height,
                                                     const std::string& title, bool visible,
                                                     std::string* error) {
  auto context = std::make_unique<GlfwContext>();
  if (!context->init(width, height, title, visible, error)) return nullptr;
  return context;
}

}  // namespace tetlod::render
