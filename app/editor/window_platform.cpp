#include "app/editor/window_platform.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/gl.h"  // before GLFW, which must not include GL itself
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>

#include "app/editor/editor.h"
#include "app/editor/input_queue.h"
#include "app/editor/imgui_context.h"
#include "app/editor/screenshot.h"

namespace mostyle::app {
namespace {

// The editor reads these keys from io.KeysDown by GLFW's codes (app/editor/editor.h).
static_assert(kKeyboardF == GLFW_KEY_F && kKeyboardZero == GLFW_KEY_0 && kKeyboardF1 == GLFW_KEY_F1 && kKeyboardKeypadZero == GLFW_KEY_KP_0,
              "app/editor/editor.h's key codes must be GLFW's");
static_assert(kKeyboardE == GLFW_KEY_E, "app/editor/editor.h's key codes must be GLFW's");
static_assert(kActionRelease == GLFW_RELEASE && kActionPress == GLFW_PRESS && kActionRepeat == GLFW_REPEAT &&
                  kModShift == GLFW_MOD_SHIFT && kModControl == GLFW_MOD_CONTROL && kModAlt == GLFW_MOD_ALT &&
                  kModSuper == GLFW_MOD_SUPER && GLFW_KEY_LEFT_SHIFT == 340 && GLFW_KEY_RIGHT_SUPER == 347,
              "app/editor/input_queue.h's values must be GLFW's");
static_assert(kKeyboardZ == GLFW_KEY_Z && kKeyboardY == GLFW_KEY_Y && kKeyboardS == GLFW_KEY_S && kKeyboardO == GLFW_KEY_O,
              "app/editor/editor.h's key codes must be GLFW's");

constexpr double kRestWakeSeconds = 0.5;  // at rest, how often to look up from waiting
constexpr int kSettleFrames = 3;          // frames drawn after an event before resting again

constexpr const char* kNoDisplay = "mostyle: no display; run under xvfb-run or pass --offscreen";

std::string g_glfw_error;  // last GLFW error, for the one-line message
void on_glfw_error(int /*code*/, const char* description) { g_glfw_error = description ? description : ""; }

bool have_display() {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x11 && *x11) || (wayland && *wayland);
}

// Screenshot frames must not depend on where the pointer is or how fast the machine is.
// Files dropped on the window go to the editor's queue; the files panel loads them.
// Input events since the start, counted by callbacks installed before ImGui's (which calls
// them on after its own): at rest, a wake-up with no event draws nothing.
int g_events = 0;
void count_key(GLFWwindow*, int, int, int, int) { ++g_events; }
void count_char(GLFWwindow*, unsigned int) { ++g_events; }
void count_button(GLFWwindow*, int, int, int) { ++g_events; }
void count_cursor(GLFWwindow*, double, double) { ++g_events; }
void count_scroll(GLFWwindow*, double, double) { ++g_events; }
void count_enter(GLFWwindow*, int) { ++g_events; }
void count_focus(GLFWwindow*, int) { ++g_events; }
void count_size(GLFWwindow*, int, int) { ++g_events; }
void count_refresh(GLFWwindow*) { ++g_events; }
void count_events(GLFWwindow* window) {
  glfwSetKeyCallback(window, count_key);
  glfwSetCharCallback(window, count_char);
  glfwSetMouseButtonCallback(window, count_button);
  glfwSetCursorPosCallback(window, count_cursor);
  glfwSetScrollCallback(window, count_scroll);
  glfwSetCursorEnterCallback(window, count_enter);
  glfwSetWindowFocusCallback(window, count_focus);
  glfwSetFramebufferSizeCallback(window, count_size);
  glfwSetWindowRefreshCallback(window, count_refresh);
}

// Keys and characters reach ImGui through a queue, a frame's worth at a time
// (app/editor/input_queue.h): no press is lost when keys come faster than frames, and what is
// typed after a shortcut waits for the field the shortcut opens.
InputQueue g_keys;
void on_key(GLFWwindow*, int key, int scancode, int action, int mods) {
  ++g_events;
  g_keys.push({KeyEvent::Kind::kKey, key, scancode, action, mods, 0});
}
void on_char(GLFWwindow*, unsigned int codepoint) {
  ++g_events;
  g_keys.push({KeyEvent::Kind::kChar, 0, 0, 0, 0, codepoint});
}
// Before each frame: the events it takes, through ImGui's GLFW back-end; all that was typed at
// once while a text field has the keyboard.
void deliver_keys(GLFWwindow* window) {
  for (const KeyEvent& e : g_keys.take_frame(ImGui::GetIO().WantTextInput)) {
    if (e.kind == KeyEvent::Kind::kKey) ImGui_ImplGlfw_KeyCallback(window, e.key, e.scancode, e.action, e.mods);
    else ImGui_ImplGlfw_CharCallback(window, e.codepoint);
  }
}

void on_drop(GLFWwindow* window, int count, const char** paths) {
  ++g_events;
  auto* editor = static_cast<Editor*>(glfwGetWindowUserPointer(window));
  if (editor == nullptr || count <= 0) return;
  editor->drop_files(std::vector<std::string>(paths, paths + count));
}

// The window's close button: the editor asks first when there are unsaved edits (Save, Discard,
// Cancel); the loop ends once it may close.
void on_close(GLFWwindow* window) {
  ++g_events;
  glfwSetWindowShouldClose(window, GLFW_FALSE);
  if (auto* editor = static_cast<Editor*>(glfwGetWindowUserPointer(window))) editor->request_close();
}

void neutralise_input() {
  ImGuiIO& io = ImGui::GetIO();
  io.DeltaTime = kScreenshotDeltaS;
  io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
  for (bool& down : io.MouseDown) down = false;
  io.MouseWheel = io.MouseWheelH = 0.0f;
}

// A window with a GL 3.3 core context made current; null after one line on stderr.
GLFWwindow* open_window(const EditorOptions& options, bool screenshot) {
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, 0);  // the viewport multisamples in its own target
  glfwWindowHint(GLFW_RESIZABLE, screenshot ? GLFW_FALSE : GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(options.width, options.height, "mostyle", nullptr, nullptr);
  if (window == nullptr) {
    std::fprintf(stderr, "%s (%s)\n", kNoDisplay, g_glfw_error.c_str());
    return nullptr;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(screenshot ? 0 : 1);
  return window;
}

// The window's input goes to `editor`: keys and text through the key queue, dropped files, the
// close button (unless a screenshot is taken), and a finished background job wakes the loop.
void connect_window(GLFWwindow* window, Editor& editor, bool screenshot) {
  count_events(window);
  ImGui_ImplGlfw_InitForOpenGL(window, /*install_callbacks=*/true);
  glfwSetKeyCallback(window, on_key);  // instead of ImGui's, which deliver_keys calls
  glfwSetCharCallback(window, on_char);
  glfwSetWindowUserPointer(window, &editor);
  // A finished background job wakes the loop below from waiting (glfwPostEmptyEvent may be
  // called from any thread), so its result shows at once, not at the next input.
  editor.set_wake([] { glfwPostEmptyEvent(); });
  glfwSetDropCallback(window, on_drop);
  if (!screenshot) glfwSetWindowCloseCallback(window, on_close);
}

void disconnect_window(GLFWwindow* window) {
  glfwSetDropCallback(window, nullptr);
  glfwSetWindowCloseCallback(window, nullptr);
  glfwSetWindowUserPointer(window, nullptr);
  ImGui_ImplGlfw_Shutdown();
}

// The frames until the window closes (or, for a screenshot, the frame it is taken at): the exit
// status.
int run_frames(GLFWwindow* window, Editor& editor, const EditorOptions& options, bool screenshot) {
  int status = 0;
  double last = glfwGetTime();
  int settle = 0;  // frames still drawn after the last event (ImGui needs a few to settle)
  for (int frame = 0; !glfwWindowShouldClose(window) && !editor.may_close(); ++frame) {
    // At rest (paused, engine idle) wait for input instead of drawing 60 frames a second;
    // the timeout keeps a finished background job from waiting long to be shown.
    if (!screenshot && !editor.animating() && !editor.settling() && settle <= 0 && g_keys.empty()) {
      const int before = g_events;
      glfwWaitEventsTimeout(kRestWakeSeconds);
      if (g_events == before && !editor.animating()) continue;  // nothing happened: nothing to draw
      settle = kSettleFrames;
    } else {
      glfwPollEvents();
      --settle;
    }
    deliver_keys(window);
    ImGui_ImplGlfw_NewFrame();
    const double now = glfwGetTime();
    FrameInput input;
    glfwGetFramebufferSize(window, &input.framebuffer_size.x, &input.framebuffer_size.y);
    input.delta_s = static_cast<float>(now - last);
    last = now;
    if (screenshot) {
      neutralise_input();
      input.delta_s = kScreenshotDeltaS;
    }
    if (input.framebuffer_size.x > 0 && input.framebuffer_size.y > 0) editor.frame(input);  // minimised: skip
    if (status == 0 && !editor.scripted_save_error().empty()) {  // --save-session: said once, on stderr too
      std::fprintf(stderr, "mostyle: %s\n", editor.scripted_save_error().c_str());
      status = 1;
    }
    if (screenshot && frame + 1 == kScreenshotFrames)
      return std::max(status, write_screenshot(input.framebuffer_size, options.screenshot_path));
    glfwSwapBuffers(window);
  }
  return status;
}

}  // namespace

int run_window(const EditorOptions& options) {
  if (!have_display()) {
    std::fprintf(stderr, "%s\n", kNoDisplay);
    return 1;
  }
  glfwSetErrorCallback(on_glfw_error);
  if (!glfwInit()) {
    std::fprintf(stderr, "%s (%s)\n", kNoDisplay, g_glfw_error.c_str());
    return 1;
  }
  const bool screenshot = !options.screenshot_path.empty();
  GLFWwindow* window = open_window(options, screenshot);
  if (window == nullptr) {
    glfwTerminate();
    return 1;
  }
  int status = 0;
  {
    ImGuiContextScope imgui(/*persist_layout=*/!screenshot);
    Editor editor(options);
    editor.set_deterministic(screenshot);
    if (screenshot) editor.wait_for_engine();  // the same aligned, decomposed pair every run
    connect_window(window, editor, screenshot);
    try {
      // A screenshot of takes that did not load would show nothing: their one sentence, exit 1.
      if (screenshot && !editor.engine().error().empty()) throw std::runtime_error(editor.engine().error());
      editor.init_graphics();
      status = run_frames(window, editor, options, screenshot);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mostyle: %s\n", e.what());
      status = 1;
    }
    editor.shutdown_graphics();
    disconnect_window(window);
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  return status;
}

}  // namespace mostyle::app
