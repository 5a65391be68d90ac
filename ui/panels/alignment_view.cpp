#include "ui/panels/alignment_view.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include <imgui.h>

#include "engine/align/warp_position.h"
#include "engine/io/motion_file.h"
#include "ui/model/take_structure.h"
#include "ui/panels/plot.h"
#include "ui/panels/structure_strip.h"
#include "ui/panels/theme.h"

namespace mostyle::ui {
namespace {
constexpr int kMatchLines = 40;  // lines joining matched frames in the "before" plot

// A signal's value at fractional frame t (linear).
double sample(const Eigen::MatrixXd& signal, double t, int column) {
  const double last = static_cast<double>(signal.rows() - 1);
  t = std::clamp(t, 0.0, last);
  const int i = static_cast<int>(std::floor(t));
  const int k = std::min(i + 1, static_cast<int>(last));
  const double u = t - i;
  return (1.0 - u) * signal(i, column) + u * signal(k, column);
}

// Heat colour for a normalised cost: dark blue (low) to warm yellow (high).
ImU32 heat(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  const float r = std::min(1.0f, 1.6f * v), g = std::pow(v, 1.6f) * 0.95f, b = 0.35f + 0.4f * (1.0f - v) - 0.3f * v;
  return ImGui::ColorConvertFloat4ToU32(ImVec4(0.08f + 0.9f * r, 0.06f + g, std::max(0.05f, b), 1.0f));
}

// The output frame showing take `take`'s warp sample u (the first at or after it, the last when
// none), or -1 without a result: the output's frames are common-timeline samples, found on the
// warp (warp_position.h), in order.
int output_frame_at(const PreparedTakes& p, int take, const MixResult* result, double u) {
  if (result == nullptr || result->sample.size() == 0) return -1;
  const TimeWarp& warp = p.takes[static_cast<size_t>(take)].alignment.warp;
  Eigen::Index lo = 0, hi = result->sample.size() - 1;
  while (lo < hi) {
    const Eigen::Index mid = (lo + hi) / 2;
    if (warp_position(warp, p.timeline, take, result->sample[mid]) < u) lo = mid + 1;
    else hi = mid;
  }
  return static_cast<int>(lo);
}
}  // namespace

std::string short_take_name(const PreparedTakes& p, int take) {
  std::vector<std::string> sources;
  for (const PreparedTake& t : p.takes) sources.push_back(t.clip->source);
  return distinct_take_labels(sources)[static_cast<size_t>(take)];
}

MatchedFrames matched_frames_in_files(const PreparedTakes& p, int take) {
  MatchedFrames m;
  if (take < 1 || take >= p.size() || p.fps <= 0.0) return m;
  const Alignment& al = p.takes[static_cast<size_t>(take)].alignment;
  // A working-rate frame of take t as its file counts it, inside the file.
  auto in_file = [&](double frame, int t) {
    const Clip& clip = *p.takes[static_cast<size_t>(t)].clip;
    const double at = clip.fps() > 0.0 ? frame * clip.fps() / p.fps : frame;
    return std::clamp(static_cast<int>(std::lround(at)), 0, std::max(clip.frames() - 1, 0));
  };
  m.reference_first = in_file(al.a_first, 0);
  m.reference_last = in_file(al.a_last, 0);
  double first = al.b_first, last = al.b_last;
  if (al.by_cycles()) {  // the registered take's frames back to its own: the lowest and highest used
    double lo = INFINITY, hi = -INFINITY;
    for (int k = std::max(al.b_first, 0); k <= al.b_last && k < al.b_source.size(); ++k) {
      if (std::isnan(al.b_source[k])) continue;
      lo = std::min(lo, al.b_source[k]);
      hi = std::max(hi, al.b_source[k]);
    }
    if (lo <= hi) {
      first = lo;
      last = hi;
    }
  }
  m.take_first = in_file(first, take);
  m.take_last = in_file(last, take);
  return m;
}

bool alignment_plottable(const PreparedTakes& p, int take) {
  if (take < 1 || take >= p.size()) return false;
  const Alignment& al = p.takes[static_cast<size_t>(take)].alignment;
  return al.feature.a.rows() >= 2 && al.feature.b.rows() >= 2 && !al.path.empty();
}

namespace {

// The aligned take as the plots show it: the aligned joint's signals (frames x columns, file
// units) of the reference (a) and of the take (b), the coordinate shown and its range, the warp
// sample at the playhead, and the two takes' labels and colours.
struct PairPlot {
  const PreparedTakes& p;
  int take;
  const Alignment& al;
  const Eigen::MatrixXd& sa;
  const Eigen::MatrixXd& sb;
  const TimeWarp& warp;
  int fa, fb, samples;
  int col;                // the coordinate shown
  double lo, hi, span;    // its range over both takes
  double current_u;       // the warp sample the playhead shows
  std::string name_a, name_b;  // "A" and "B" in a pair; "reference" and the take's name
  ImU32 color_a, color_b;
};

// The warp's first sample at or after the reference's frame i (the last when none).
double sample_at_a_frame(const TimeWarp& warp, int samples, int i) {
  const double* at = std::lower_bound(warp.a.data(), warp.a.data() + samples, double(i));
  return static_cast<double>(std::min<std::ptrdiff_t>(at - warp.a.data(), samples - 1));
}

// Take `take`'s plot of the coordinate the document asks for, at the playhead.
PairPlot pair_plot(const EditorState& state, const PreparedTakes& p, int take, const MixResult* result) {
  const Alignment& al = p.takes[static_cast<size_t>(take)].alignment;
  const Eigen::MatrixXd& sa = al.feature.a;
  const Eigen::MatrixXd& sb = al.feature.b;
  const int col = std::clamp(state.document.controls.dtw_coordinate, 0, static_cast<int>(sa.cols()) - 1);
  const double lo = std::min(sa.col(col).minCoeff(), sb.col(col).minCoeff());
  double hi = std::max(sa.col(col).maxCoeff(), sb.col(col).maxCoeff());
  if (hi <= lo) hi = lo + 1.0;
  const int current = state.shown.empty() ? 0 : frame_at(state.shown.back(), state.playback.time_s);
  const double current_u = result != nullptr && current < result->sample.size()
                               ? warp_position(al.warp, p.timeline, take, result->sample[current])
                               : 0.0;
  const int n = p.size();
  const std::string a = *take_letter(0, n) ? take_letter(0, n) : "reference";
  const std::string b = *take_letter(take, n) ? take_letter(take, n) : short_take_name(p, take);
  return PairPlot{p, take, al, sa, sb, al.warp, static_cast<int>(sa.rows()), static_cast<int>(sb.rows()),
                  al.warp.samples(), col, lo, hi, hi - lo, current_u, a, b, take_color_u32(0), take_color_u32(take)};
}

// The coordinate shown, what the take was aligned on and the frames matched, its warnings.
void draw_header(DocumentControls& c, const PairPlot& v) {
  const PreparedTakes& p = v.p;
  const Alignment& al = v.al;
  ImGui::SetNextItemWidth(110.0f);
  ImGui::Combo("##coordinate", &c.dtw_coordinate, "lateral x\0height y\0forward z\0");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Which coordinate of the aligned joint the plots show");
  ImGui::SameLine();
  std::string joints;
  for (int k : al.feature.columns) joints += (joints.empty() ? "" : ", ") + p.takes[0].names[static_cast<size_t>(k)];
  const MatchedFrames matched = matched_frames_in_files(p, v.take);  // as each file counts its frames
  ImGui::TextColored(ImVec4(0.6f, 0.62f, 0.66f, 1.0f), "%s %d-%d, %s %d-%d matched", v.name_a.c_str(),
                     matched.reference_first, matched.reference_last, v.name_b.c_str(), matched.take_first,
                     matched.take_last);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Aligned on %s (%s), %s DTW. Frames outside the matched ranges (shaded) are left out of the "
                      "result.\n%d x %d frames at %.0f fps, cost %.3g",
                      align_on_name(al.feature.on), joints.c_str(), dtw_method_name(al.options.method),
                      static_cast<int>(al.feature.a.rows()), static_cast<int>(al.feature.b.rows()), p.fps, al.cost);
  // The cost matrix's colours: a gradient from a good match to a poor one.
  ImGui::SameLine();
  ImGui::TextColored(kDimColor, "cost: low");
  ImGui::SameLine(0.0f, 4.0f);
  const ImVec2 at = ImGui::GetCursorScreenPos();
  const float bar_w = 48.0f, bar_h = ImGui::GetTextLineHeight();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  for (int k = 0; k < 12; ++k)
    dl->AddRectFilled(ImVec2(at.x + k * bar_w / 12.0f, at.y + 2.0f), ImVec2(at.x + (k + 1) * bar_w / 12.0f + 0.5f, at.y + bar_h - 2.0f),
                      heat(static_cast<float>(k) / 11.0f));
  ImGui::Dummy(ImVec2(bar_w, bar_h));
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The cost matrix's colours: how unlike the reference's frame (down) is to the take's (across); "
                      "the path keeps to the low cost");
  ImGui::SameLine(0.0f, 4.0f);
  ImGui::TextColored(kDimColor, "high");
  ImGui::PushTextWrapPos(0.0f);  // warnings wrap inside the panel
  for (const std::string& w : al.warnings) ImGui::TextColored(kWarningColor, "%s", w.c_str());
  ImGui::PopTextWrapPos();
}

// Under the "before" plot's lines: the matched ranges shaded, matched frames joined, and ticks
// where each take's cycles begin.
void draw_before_marks(const PairPlot& v, const PlotArea& before) {
  const Alignment& al = v.al;
  const double lo = v.lo, hi = v.hi, span = v.span;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->PushClipRect(before.min, before.max, true);
  dl->AddRectFilled(before.to_screen(al.a_first, hi + 0.1 * span), before.to_screen(al.a_last, lo - 0.05 * span),
                    IM_COL32(230, 140, 60, 28));
  dl->AddRectFilled(before.to_screen(al.b_first, hi - 1.1 * span), before.to_screen(al.b_last, lo - 1.15 * span),
                    IM_COL32(80, 150, 240, 28));
  const size_t n = al.path.size();
  const size_t stride = std::max<size_t>(1, n / kMatchLines);
  for (size_t s = 0; s < n; s += stride) {
    const auto [i, j] = al.path[s];
    dl->AddLine(before.to_screen(i, v.sa(i, v.col)), before.to_screen(j, v.sb(j, v.col) - 1.05 * span),
                IM_COL32(150, 155, 165, 90), 1.0f);
  }
  // Each take's rests shaded grey across its band, its actions (and the strokes or steps in them)
  // a strip at the band's outer edge, on the frames plotted: the take's through its registration.
  auto shade = [&](const PreparedTake& t, int frames, const std::function<double(int)>& own, double top,
                   double bottom, double strip_top, double strip_bottom, ImU32 color) {
    const ImU32 strip = (color & 0x00FFFFFFu) | 0x90000000u;
    for (const StructureSpan& r : structure_spans(t, frames, own)) {
      if (r.structure.part == FramePart::kRest)
        dl->AddRectFilled(before.to_screen(r.begin, top), before.to_screen(r.end, bottom), IM_COL32(150, 150, 160, 45));
      else if (r.structure.part != FramePart::kPosture)
        dl->AddRectFilled(before.to_screen(r.begin, strip_top), before.to_screen(r.end, strip_bottom), strip);
    }
  };
  const PreparedTake& take = v.p.takes[static_cast<size_t>(v.take)];
  shade(v.p.takes[0], v.fa, [](int i) { return double(i); }, hi + 0.1 * span, lo - 0.05 * span, hi + 0.1 * span,
        hi + 0.03 * span, v.color_a);
  shade(take, v.fb, [&](int j) { return own_frame(take, j); }, hi - 1.1 * span, lo - 1.15 * span, lo - 1.08 * span,
        lo - 1.15 * span, v.color_b);
  // Where each take's cycles begin (engine/align/cycles.h): ticks at the top of the reference's
  // band and the bottom of the take's.
  for (const Cycle& c : v.p.takes[0].timeline_cycles().cycles)
    dl->AddLine(before.to_screen(c.begin, hi + 0.1 * span), before.to_screen(c.begin, hi - 0.1 * span), v.color_a, 2.0f);
  for (const Cycle& c : take.timeline_cycles().cycles)
    dl->AddLine(before.to_screen(c.begin, lo - 1.15 * span), before.to_screen(c.begin, lo - 0.95 * span), v.color_b,
                2.0f);
  dl->PopClipRect();
}

// Before warping: the reference above, the take below, each on its own timeline; matched frames
// joined, the matched ranges shaded. A group `width` wide (-1: the panel's width).
PlotArea draw_before(const PairPlot& v, float width, float plot_h) {
  const double lo = v.lo, hi = v.hi, span = v.span;
  const int col = v.col;
  ImGui::BeginGroup();
  ImGui::TextUnformatted("before warping");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("%s above, %s below, each on its own timeline; matched frames joined; shaded grey: rests; a "
                      "strip at the edge: the actions between them; ticks where each take's cycles (steps or "
                      "strokes) begin", v.name_a.c_str(), v.name_b.c_str());
  const int frames = std::max(v.fa, v.fb);
  PlotArea before = begin_plot("##before", width, plot_h, 0.0, frames - 1, lo - 1.15 * span, hi + 0.1 * span);
  draw_before_marks(v, before);
  plot_line(before, v.fa, [&](int i, double* x, double* y) { *x = i; *y = v.sa(i, col); }, v.color_a);
  plot_line(before, v.fb, [&](int j, double* x, double* y) { *x = j; *y = v.sb(j, col) - 1.05 * span; }, v.color_b);
  plot_legend(before, 0, v.name_a.c_str(), v.color_a);
  plot_legend(before, 1, v.name_b.c_str(), v.color_b);
  plot_axis_label(before, "frames");
  ImGui::EndGroup();
  return before;
}

// Beside the cost matrix, each take's structure along its frames (ui/panels/structure_strip.h):
// the take's above, across, the reference's at the left, down; hover names a frame's.
void draw_structure_beside(const PairPlot& v, const PlotArea& cost, ImVec2 corner) {
  const PreparedTake& ref = v.p.takes[0];
  const PreparedTake& take = v.p.takes[static_cast<size_t>(v.take)];
  const ImVec2 across_min(cost.min.x, corner.y), across_max(cost.max.x, cost.min.y - 2.0f);
  const ImVec2 down_min(corner.x, cost.min.y), down_max(cost.min.x - 2.0f, cost.max.y);
  draw_structure_strip(take, across_min, across_max, v.fb, false, v.color_b, [&](int j) { return own_frame(take, j); });
  draw_structure_strip(ref, down_min, down_max, v.fa, true, v.color_a, [](int i) { return double(i); });
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  if (ImGui::IsMouseHoveringRect(across_min, across_max)) {
    const int j = std::clamp(static_cast<int>(cost.x_at(mouse.x)), 0, v.fb - 1);
    ImGui::SetTooltip("%s frame %d: %s", v.name_b.c_str(), j, frame_structure_words(take, own_frame(take, j)).c_str());
  } else if (ImGui::IsMouseHoveringRect(down_min, down_max)) {
    const int i = std::clamp(static_cast<int>(cost.y_at(mouse.y)), 0, v.fa - 1);
    ImGui::SetTooltip("%s frame %d: %s", v.name_a.c_str(), i, frame_structure_words(ref, i).c_str());
  }
}

// The cost matrix (the reference's frames down, the take's across) with the path and the
// playhead on it, each take's structure beside it (draw_structure_beside). `side`: the whole
// square's, the structure's strips in it.
PlotArea draw_cost(const PairPlot& v, const DtwCostImage& img, float side) {
  const TimeWarp& warp = v.warp;
  ImGui::BeginGroup();
  ImGui::TextUnformatted("cost and path");
  const float strip = std::max(6.0f, 0.5f * ImGui::GetFontSize());
  const ImVec2 corner = ImGui::GetCursorScreenPos();
  const float plot_side = side - strip - ImGui::GetStyle().ItemSpacing.y;
  ImGui::Dummy(ImVec2(side, strip));
  ImGui::Dummy(ImVec2(strip, plot_side));
  ImGui::SameLine(0.0f, 0.0f);
  // y down: frame 0 at the top
  PlotArea cost = begin_plot("##cost", plot_side, plot_side, 0.0, v.fb, v.fa, 0.0);
  draw_structure_beside(v, cost, corner);
  if (img.rows > 0 && img.cols > 0) {
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const float cw = (cost.max.x - cost.min.x) / img.cols, ch = (cost.max.y - cost.min.y) / img.rows;
    for (int r = 0; r < img.rows; ++r)
      for (int k = 0; k < img.cols; ++k)
        dl->AddRectFilled(ImVec2(cost.min.x + k * cw, cost.min.y + r * ch),
                          ImVec2(cost.min.x + (k + 1) * cw + 0.5f, cost.min.y + (r + 1) * ch + 0.5f), heat(img.cost(r, k)));
    plot_line(cost, v.samples,
              [&](int u, double* x, double* y) {
                *x = warp.b[u] + 0.5;
                *y = warp.a[u] + 0.5;
              },
              IM_COL32(255, 255, 255, 230), 2.0f);
    const int u = std::clamp(static_cast<int>(std::lround(v.current_u)), 0, v.samples - 1);
    dl->AddCircleFilled(cost.to_screen(warp.b[u] + 0.5, warp.a[u] + 0.5), 4.5f, color_blend());
    const std::string across = v.name_b + " ->", down = v.name_a + " v";
    const float names = ImGui::CalcTextSize(across.c_str()).x + ImGui::CalcTextSize(down.c_str()).x;
    if (cost.max.x - cost.min.x > names + 2.0f * ImGui::GetFontSize()) {  // both names, apart
      plot_axis_label(cost, across.c_str());
      plot_axis_label(cost, down.c_str(), /*left=*/true);
    }
  }
  ImGui::EndGroup();
  return cost;
}

// Both takes on the warp's samples. *hovered_u: the sample under the mouse, when it is over the plot.
PlotArea draw_after(const PairPlot& v, float height, double* hovered_u) {
  const TimeWarp& warp = v.warp;
  const int col = v.col, samples = v.samples;
  ImGui::TextUnformatted("after warping");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("%s and %s on the common timeline (the warp's samples); under them, how well they match: the\n"
                      "local cost over the path's typical cost (1 typical; above the red line, shaded, poor)",
                      v.name_a.c_str(), v.name_b.c_str());
  PlotArea after = begin_plot("##after", -1.0f, height, 0.0, samples - 1, v.lo - 0.08 * v.span, v.hi + 0.08 * v.span);
  plot_line(after, samples, [&](int u, double* x, double* y) { *x = u; *y = sample(v.sa, warp.a[u], col); }, v.color_a, 2.0f);
  plot_line(after, samples, [&](int u, double* x, double* y) { *x = u; *y = sample(v.sb, warp.b[u], col); }, v.color_b);
  plot_vline(after, v.current_u, IM_COL32(255, 255, 255, 140));
  plot_legend(after, 0, v.name_a.c_str(), v.color_a);
  plot_legend(after, 1, v.name_b.c_str(), v.color_b);
  if (after.hovered) *hovered_u = std::clamp(after.x_at(ImGui::GetIO().MousePos.x), 0.0, samples - 1.0);
  return after;
}

// The match quality under the "after" plot: local cost over the path's typical cost, 1 a typical
// match, above kPoorMatchRatio poor (shaded). *hovered_u as draw_after's.
PlotArea draw_quality(const PairPlot& v, float height, double* hovered_u) {
  const Alignment& al = v.al;
  const int samples = v.samples;
  const double top = std::max(kPoorMatchRatio * 1.5, al.cost_ratio.size() ? al.cost_ratio.maxCoeff() : 1.0);
  PlotArea quality = begin_plot("##quality", -1.0f, height, 0.0, samples - 1, 0.0, top);
  {
    ImDrawList* dl = ImGui::GetWindowDrawList();
    for (const auto& [first, last] : al.poor)
      dl->AddRectFilled(quality.to_screen(first, top), quality.to_screen(last, 0.0), IM_COL32(230, 80, 60, 70));
    dl->AddLine(quality.to_screen(0, kPoorMatchRatio), quality.to_screen(samples - 1, kPoorMatchRatio),
                IM_COL32(230, 80, 60, 120), 1.0f);
  }
  plot_line(quality, samples, [&](int u, double* x, double* y) { *x = u; *y = al.cost_ratio[u]; },
            IM_COL32(220, 220, 225, 220));
  plot_vline(quality, v.current_u, IM_COL32(255, 255, 255, 140));
  plot_legend(quality, 0, "match", IM_COL32(200, 200, 205, 255));
  if (quality.hovered) *hovered_u = std::clamp(quality.x_at(ImGui::GetIO().MousePos.x), 0.0, samples - 1.0);
  return quality;
}

// The frames matched at warp sample hovered_u, and a click there moves the playhead to the
// output frame that shows it.
void match_tooltip(EditorState& state, const PairPlot& v, const MixResult* blend, double hovered_u, bool clicked) {
  const TimeWarp& warp = v.warp;
  const int u = std::clamp(static_cast<int>(std::lround(hovered_u)), 0, v.samples - 1);
  const char* a = v.name_a.c_str();
  const char* b = v.name_b.c_str();
  ImGui::SetTooltip("%s frame %.1f  <->  %s frame %.1f\nmatch cost %.2f x the typical, %s runs %.2f x %s's speed\n"
                    "click: jump there",
                    a, warp.a[u], b, warp.b[u], v.al.cost_ratio[u], b, v.al.slope[u], a);
  const int frame = output_frame_at(v.p, v.take, blend, hovered_u);
  if (clicked && frame >= 0) state.playback.time_s = (frame + 0.5) / v.p.fps;
}

}  // namespace

void draw_alignment(EditorState& state, const PreparedTakes& p, int take, const MixResult* result,
                    const DtwCostImage& image) {
  if (!alignment_plottable(p, take)) {
    ImGui::TextColored(kDimColor, "Not aligned yet.");
    return;
  }
  const PairPlot v = pair_plot(state, p, take, result);
  draw_header(state.document.controls, v);

  const float line = ImGui::GetTextLineHeightWithSpacing();
  // In the layout's bottom strip (much wider than high) the views stand side by side; a panel
  // the animator made tall stacks "before" above the others.
  const ImVec2 room = ImGui::GetContentRegionAvail();
  const bool wide = room.x > 2.5f * room.y;
  const float plot_h = wide ? std::max(40.0f, room.y - line - 4.0f) : std::max(50.0f, (room.y - 2.0f * line) * 0.36f);
  double hovered_u = -1.0;  // a warp sample under the mouse
  const PlotArea before = draw_before(v, wide ? 0.45f * room.x : -1.0f, plot_h);
  if (wide) ImGui::SameLine();
  if (before.hovered) {
    const int i = std::clamp(static_cast<int>(std::lround(before.x_at(ImGui::GetIO().MousePos.x))), 0, v.fa - 1);
    hovered_u = sample_at_a_frame(v.warp, v.samples, i);
  }

  // Below (or beside): the cost matrix (the reference's frames down, the take's across, the path
  // and the playhead on it) beside the signals after warping, over the warp's samples, with the
  // match quality under them.
  const float side = std::clamp(std::min(ImGui::GetContentRegionAvail().y - line - 4.0f,
                                         0.5f * ImGui::GetContentRegionAvail().x),
                                60.0f, 600.0f);
  const PlotArea cost = draw_cost(v, image, side);
  ImGui::SameLine();
  ImGui::BeginGroup();
  // Tall enough for its curve and its legend to read (a third of the square beside it).
  const float quality_h = std::max(1.6f * ImGui::GetFontSize(), 0.4f * side);
  const PlotArea after = draw_after(v, side - quality_h - 4.0f, &hovered_u);
  const PlotArea quality = draw_quality(v, quality_h, &hovered_u);
  ImGui::EndGroup();
  if (cost.hovered) {
    const int i = std::clamp(static_cast<int>(cost.y_at(ImGui::GetIO().MousePos.y)), 0, v.fa - 1);
    hovered_u = sample_at_a_frame(v.warp, v.samples, i);
  }
  if (hovered_u >= 0)
    match_tooltip(state, v, result, hovered_u, before.clicked || after.clicked || quality.clicked || cost.clicked);
}

}  // namespace mostyle::ui
