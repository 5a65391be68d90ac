#include "app/editor/offscreen_platform.h"

#include <cfloat>
#include <cstdint>
#include <cstdio>
#include <chrono>
#include <exception>
#include <stdexcept>
#include <vector>

#include "render/gl.h"
#include <GL/osmesa.h>
#include <imgui.h>

#include "app/editor/editor.h"
#include "app/editor/imgui_context.h"
#include "app/editor/screenshot.h"

namespace mostyle::app {

int run_offscreen(const EditorOptions& options) {
  const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA,
                            OSMESA_DEPTH_BITS, 24,
                            OSMESA_STENCIL_BITS, 8,
                            OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION, 3,
                            OSMESA_CONTEXT_MINOR_VERSION, 3,
                            0};
  OSMesaContext context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (context == nullptr) {
    std::fprintf(stderr, "mostyle: OSMesa could not create an OpenGL 3.3 core context\n");
    return 1;
  }
  const glm::ivec2 size(options.width, options.height);
  std::vector<std::uint8_t> buffer(static_cast<size_t>(size.x) * static_cast<size_t>(size.y) * 4);
  if (!OSMesaMakeCurrent(context, buffer.data(), GL_UNSIGNED_BYTE, size.x, size.y)) {
    std::fprintf(stderr, "mostyle: OSMesa could not make its context current\n");
    OSMesaDestroyContext(context);
    return 1;
  }

  int status = 0;
  {
    ImGuiContextScope imgui(/*persist_layout=*/false);
    ImGuiIO& io = ImGui::GetIO();
    io.BackendPlatformName = "mostyle_offscreen";
    Editor editor(options);
    editor.set_deterministic(true);
    editor.wait_for_engine();  // the same aligned, decomposed pair every run
    // --live: a second of the stream styled first (or its end, or its error in the Files panel).
    if (!options.live_address.empty()) editor.wait_for_live(1.0, std::chrono::seconds(60));
    try {
      // Takes that did not load leave nothing to show: their one sentence, exit 1, no picture.
      if (!editor.engine().error().empty()) throw std::runtime_error(editor.engine().error());
      editor.init_graphics();
      for (int frame = 0; frame < kScreenshotFrames; ++frame) {
        // What a platform back-end would do: display size, time step, no pointer.
        io.DisplaySize = ImVec2(static_cast<float>(size.x), static_cast<float>(size.y));
        io.DisplayFramebufferScale = ImVec2(1.0f, 1.0f);
        io.DeltaTime = kScreenshotDeltaS;
        io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
        editor.frame(FrameInput{size, kScreenshotDeltaS});
      }
      status = write_screenshot(size, options.screenshot_path);
      if (!editor.scripted_save_error().empty() || editor.scripted_save_pending()) {
        std::fprintf(stderr, "mostyle: %s\n", editor.scripted_save_pending() ? "the session was not saved: the takes did not finish loading" : editor.scripted_save_error().c_str());
        status = 1;
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mostyle: %s\n", e.what());
      status = 1;
    }
    editor.shutdown_graphics();
  }
  OSMesaDestroyContext(context);
  return status;
}

}  // namespace mostyle::app
