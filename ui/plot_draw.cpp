#include "ui/plot_draw.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

namespace dampbound::ui::detail {

namespace {
constexpr float kSuperscriptScale = 0.72f;
/// Far-off pixel values are clamped to this distance beyond the area before going to float;
/// slopes inside the area change by well under a pixel.
constexpr double kFar = 1e6;

ImVec2 vec(double x, double y) { return ImVec2(static_cast<float>(x), static_cast<float>(y)); }

unsigned alpha_of(ImU32 c) { return (c >> IM_COL32_A_SHIFT) & 0xFFu; }
}  // namespace

ImVec2 text_size(const TextFont& f, const std::string& s) {
  return f.font->CalcTextSizeA(f.size, FLT_MAX, 0.0f, s.c_str(), s.c_str() + s.size());
}

void draw_text(ImDrawList* dl, const TextFont& f, ImVec2 pos, ImU32 col, const std::string& s) {
  dl->AddText(f.font, f.size, ImVec2(std::round(pos.x), std::round(pos.y)), col, s.c_str(),
              s.c_str() + s.size());
}

void draw_text_vertical(ImDrawList* dl, const TextFont& f, ImVec2 c, ImU32 col,
                        const std::string& s) {
  const ImVec2 sz = text_size(f, s);
  // Lay the text out horizontally in the middle of the clip rectangle (ImGui culls glyphs
  // outside it), then turn the new vertices by 90 degrees, (dx, dy) -> (dy, -dx), about that
  // middle and move them to c.
  const ImVec2 lo = dl->GetClipRectMin(), hi = dl->GetClipRectMax();
  const ImVec2 m(std::round(0.5f * (lo.x + hi.x)), std::round(0.5f * (lo.y + hi.y)));
  const ImVec2 cr(std::round(c.x), std::round(c.y));
  const int v0 = dl->VtxBuffer.Size;
  draw_text(dl, f, ImVec2(m.x - sz.x * 0.5f, m.y - sz.y * 0.5f), col, s);
  for (int i = v0; i < dl->VtxBuffer.Size; ++i) {
    ImVec2& p = dl->VtxBuffer[i].pos;
    const float dx = p.x - m.x, dy = p.y - m.y;
    p = ImVec2(cr.x + dy, cr.y - dx);
  }
}

ImVec2 tick_label_size(const TextFont& f, const Tick& t) {
  if (!t.pow10) return text_size(f, t.label);
  const ImVec2 base = text_size(f, "10");
  const ImVec2 ex = text_size({f.font, f.size * kSuperscriptScale}, std::to_string(t.exponent));
  return ImVec2(base.x + ex.x + 1.0f, base.y + std::round(0.3f * f.size));
}

void draw_tick_label(ImDrawList* dl, const TextFont& f, ImVec2 pos, ImU32 col, const Tick& t) {
  if (!t.pow10) {
    draw_text(dl, f, pos, col, t.label);
    return;
  }
  const ImVec2 base = text_size(f, "10");
  draw_text(dl, f, ImVec2(pos.x, pos.y + std::round(0.3f * f.size)), col, "10");
  draw_text(dl, {f.font, f.size * kSuperscriptScale}, ImVec2(pos.x + base.x + 1.0f, pos.y), col,
            std::to_string(t.exponent));
}

void draw_heatmap(ImDrawList* dl, const PlotLayout& lay, const PlotHeatmap& hm) {
  const int nx = hm.nx(), ny = hm.ny();
  if (nx == 0 || ny == 0 || hm.cell_color.size() < static_cast<size_t>(nx) * ny) return;
  // Cell edges snap to whole pixels, so each pixel belongs to exactly one cell: a map finer
  // than the screen costs at most one rectangle per pixel, and cells tile without seams.
  const PixelRect& a = lay.area;
  auto snap = [](double p, double lo, double hi) {
    return std::isnan(p) ? std::numeric_limits<float>::quiet_NaN()
                         : static_cast<float>(std::round(std::clamp(p, lo, hi)));
  };
  std::vector<float> xe(nx + 1), ye(ny + 1);
  for (int i = 0; i <= nx; ++i) xe[i] = snap(lay.x.to_px(hm.x_edges[i]), a.x0, a.x1);
  for (int j = 0; j <= ny; ++j) ye[j] = snap(lay.y.to_px(hm.y_edges[j]), a.y0, a.y1);
  for (int j = 0; j < ny; ++j) {
    const float top = std::min(ye[j], ye[j + 1]), bot = std::max(ye[j], ye[j + 1]);
    if (!(bot > top)) continue;  // also skips NaN edges
    float run_x0 = 0.0f, run_x1 = 0.0f;
    ImU32 run_col = 0;
    auto flush = [&] {
      if (run_col != 0) dl->AddRectFilled(ImVec2(run_x0, top), ImVec2(run_x1, bot), run_col);
      run_col = 0;
    };
    for (int i = 0; i < nx; ++i) {
      const float x0 = xe[i], x1 = xe[i + 1];
      if (!(x1 > x0)) continue;
      const ImU32 c = hm.cell_color[static_cast<size_t>(j) * nx + i];
      if (alpha_of(c) == 0) {
        flush();
        continue;
      }
      if (c == run_col && x0 == run_x1) {
        run_x1 = x1;
        continue;
      }
      flush();
      run_col = c;
      run_x0 = x0;
      run_x1 = x1;
    }
    flush();
  }
}

void draw_band(ImDrawList* dl, const PlotLayout& lay, const PlotBand& band) {
  const size_t n = std::min({band.x.size(), band.y_lo.size(), band.y_hi.size()});
  if (n < 2) return;
  const PixelRect& a = lay.area;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // +inf: the top edge; -inf (or <= 0 on a log axis): the bottom edge; NaN: no sample.
  auto ypix = [&](double v) {
    if (std::isnan(v)) return nan;
    if (v == std::numeric_limits<double>::infinity()) return a.y0 - 2.0;
    if (v == -std::numeric_limits<double>::infinity() || (lay.y.log && v <= 0.0)) return a.y1 + 2.0;
    return std::clamp(lay.y.to_px(v), a.y0 - kFar, a.y1 + kFar);
  };
  std::vector<BandSample> px(n);
  for (size_t i = 0; i < n; ++i) {
    const double x = lay.x.to_px(band.x[i]);
    px[i] = {std::isnan(x) ? x : std::clamp(x, a.x0 - kFar, a.x1 + kFar), ypix(band.y_lo[i]),
             ypix(band.y_hi[i])};
  }
  // Thousands of sub-pixel slivers cost a software rasteriser dearly: one column, one quad.
  if (static_cast<double>(n) > 2.0 * std::max(a.x1 - a.x0, 1.0)) px = decimate_band_columns(px);
  // Without anti-aliased fills, neighbouring quads share exact edges: no seams, no overlap.
  const ImDrawListFlags saved = dl->Flags;
  dl->Flags &= ~ImDrawListFlags_AntiAliasedFill;
  std::vector<ImVec2> poly;
  for (size_t i = 1; i < px.size(); ++i) {
    const BandSample& p = px[i - 1];
    const BandSample& q = px[i];
    if (std::isnan(p.x + p.lo + p.hi + q.x + q.lo + q.hi)) continue;
    // On screen the band is non-empty where lo is below hi: d = lo - hi >= 0.
    const double d0 = p.lo - p.hi, d1 = q.lo - q.hi;
    if (d0 >= 0.0 && d1 >= 0.0) {
      poly = {vec(p.x, p.hi), vec(q.x, q.hi), vec(q.x, q.lo), vec(p.x, p.lo)};
    } else if (d0 >= 0.0 || d1 >= 0.0) {
      const double t = d0 / (d0 - d1);  // where the curves cross
      const double xc = p.x + t * (q.x - p.x), yc = p.hi + t * (q.hi - p.hi);
      poly = d0 >= 0.0 ? std::vector<ImVec2>{vec(p.x, p.hi), vec(xc, yc), vec(p.x, p.lo)}
                       : std::vector<ImVec2>{vec(xc, yc), vec(q.x, q.hi), vec(q.x, q.lo)};
    } else {
      continue;
    }
    poly = clip_polygon(poly, a);
    if (poly.size() >= 3) {
      dl->AddConvexPolyFilled(poly.data(), static_cast<int>(poly.size()), band.color);
    }
  }
  dl->Flags = saved;
}

void draw_polyline(ImDrawList* dl, const std::vector<ImVec2>& pts, ImU32 col, float thickness,
                   bool dashed) {
  if (pts.size() < 2) return;
  auto stroke = [&](const std::vector<ImVec2>& piece) {
    for (const auto& run : split_sharp_turns(piece)) {
      if (run.size() >= 2) {
        dl->AddPolyline(run.data(), static_cast<int>(run.size()), col, ImDrawFlags_None,
                        thickness);
      }
    }
  };
  if (!dashed) {
    stroke(pts);
    return;
  }
  const float t = std::max(thickness, 1.0f);
  for (const auto& piece : dash_polyline(pts, 5.0f + 3.0f * t, 3.0f + 2.0f * t)) stroke(piece);
}

void draw_series(ImDrawList* dl, const PlotLayout& lay, const PlotSeries& s) {
  const PixelRect& a = lay.area;
  const double m = s.thickness + 2.0;
  const PixelRect clip{a.x0 - m, a.y0 - m, a.x1 + m, a.y1 + m};
  const double width = std::max(a.x1 - a.x0, 1.0);
  for (auto& line : project_polylines(s.x, s.y, lay.x, lay.y, clip)) {
    if (line.size() == 1) {
      dl->AddCircleFilled(line[0], std::max(s.thickness, 2.0f), s.color, 8);
      continue;
    }
    if (static_cast<double>(line.size()) > 2.0 * width) line = decimate_columns(line);
    draw_polyline(dl, line, s.color, s.thickness, s.dashed);
  }
}

namespace {

struct LegendEntry {
  std::string label;
  ImU32 color = 0;
  bool filled = false;
  bool dashed = false;
  float thickness = 2.0f;
};

std::vector<LegendEntry> legend_entries(const PlotSpec& spec) {
  std::vector<LegendEntry> e;
  if (spec.legend == LegendPos::Hidden) return e;
  for (const auto& s : spec.series) {
    if (!s.label.empty()) e.push_back({s.label, s.color, false, s.dashed, s.thickness});
  }
  for (const auto& b : spec.bands) {
    if (!b.label.empty()) e.push_back({b.label, b.color, true, false, 0.0f});
  }
  for (const LineAxis axis : {LineAxis::y, LineAxis::x})  // horizontal lines listed first
    for (const PlotRefLine& l : spec.ref_lines)
      if (l.axis == axis && !l.label.empty())
        e.push_back({l.label, l.color, false, l.dashed, l.thickness});
  for (const auto& c : spec.heatmap.legend) {
    if (!c.label.empty()) e.push_back({c.label, c.color, true, false, 0.0f});
  }
  return e;
}

}  // namespace

LegendMetrics::LegendMetrics(float fs)
    : pad(std::round(0.5f * fs)), row(std::round(1.35f * fs)), swatch(std::round(2.2f * fs)) {}

float LegendMetrics::column_width(float label_w) const { return pad * 1.5f + swatch + label_w; }

ImVec2 LegendMetrics::box(int entries, int columns, float label_w) const {
  const int cols = std::max(1, std::min(columns, entries));
  const int rows = (entries + cols - 1) / cols;
  return ImVec2(static_cast<float>(cols) * column_width(label_w) + pad,
                pad * 1.2f + row * static_cast<float>(rows));
}

int legend_count(const PlotSpec& spec) { return static_cast<int>(legend_entries(spec).size()); }

float legend_label_width(const PlotSpec& spec, const TextFont& f) {
  float w = 0.0f;
  for (const auto& e : legend_entries(spec)) w = std::max(w, text_size(f, e.label).x);
  return w;
}

ImVec2 legend_size(const PlotSpec& spec, const TextFont& f) {
  const int n = legend_count(spec);
  if (n == 0) return ImVec2(0.0f, 0.0f);
  return LegendMetrics(f.size).box(n, 1, legend_label_width(spec, f));
}

std::string elide(const TextFont& f, const std::string& label, float width) {
  if (text_size(f, label).x <= width) return label;
  std::string s = label;
  while (!s.empty() && text_size(f, s + "...").x > width) {
    s.pop_back();
    while (!s.empty() && (static_cast<unsigned char>(s.back()) & 0xC0) == 0x80) s.pop_back();
  }
  return s + "...";
}

void draw_legend(ImDrawList* dl, const PlotLayout& lay, const PlotSpec& spec,
                 const PlotStyle& style, const TextFont& f) {
  if (lay.legend_pos == LegendPos::Hidden) return;
  auto entries = legend_entries(spec);
  if (entries.empty()) return;
  const LegendMetrics m(f.size);
  for (auto& e : entries) e.label = elide(f, e.label, lay.legend_label_width + 0.5f);
  const ImVec2 p(static_cast<float>(lay.legend.x0), static_cast<float>(lay.legend.y0));
  const ImVec2 q(static_cast<float>(lay.legend.x1), static_cast<float>(lay.legend.y1));
  dl->AddRectFilled(p, q, style.legend_background, 3.0f);
  dl->AddRect(ImVec2(p.x + 0.5f, p.y + 0.5f), ImVec2(q.x - 0.5f, q.y - 0.5f), style.legend_border,
              3.0f);
  const int cols = std::max(1, lay.legend_columns);
  const float col_w = m.column_width(lay.legend_label_width);
  for (size_t i = 0; i < entries.size(); ++i) {
    const LegendEntry& e = entries[i];
    const int col = static_cast<int>(i) % cols, row = static_cast<int>(i) / cols;
    const float mid = std::round(p.y + m.pad * 0.6f + m.row * (static_cast<float>(row) + 0.5f));
    const float sx0 = p.x + m.pad + col_w * static_cast<float>(col), sx1 = sx0 + m.swatch;
    if (e.filled) {
      const float h = std::round(m.row * 0.32f);
      dl->AddRectFilled(ImVec2(sx0, mid - h), ImVec2(sx1, mid + h), e.color);
      if (alpha_of(e.color) < 255) {
        dl->AddRect(ImVec2(sx0, mid - h), ImVec2(sx1, mid + h), with_alpha(e.color, 200));
      }
    } else {
      draw_polyline(dl, {ImVec2(sx0, mid + 0.5f), ImVec2(sx1, mid + 0.5f)}, e.color,
                    std::min(e.thickness, 4.0f), e.dashed);
    }
    const ImVec2 ts = text_size(f, e.label);
    draw_text(dl, f, ImVec2(sx1 + m.pad * 0.8f, mid - ts.y * 0.5f), style.text, e.label);
  }
}

}  // namespace dampbound::ui::detail

namespace dampbound::ui {

size_t curve_pixels_under(const PlotLayout& lay, const PlotSpec& spec, const PixelRect& box) {
  // Pixels counted: inside the box and inside the data area (curves are clipped to it).
  const PixelRect& a = lay.area;
  const double x0 = std::max(box.x0, a.x0), y0 = std::max(box.y0, a.y0);
  const double x1 = std::min(box.x1, a.x1), y1 = std::min(box.y1, a.y1);
  if (!(x1 > x0 && y1 > y0)) return 0;
  const int px0 = static_cast<int>(std::floor(x0)), py0 = static_cast<int>(std::floor(y0));
  const int w = static_cast<int>(std::ceil(x1)) - px0, h = static_cast<int>(std::ceil(y1)) - py0;
  std::vector<unsigned char> hit(static_cast<size_t>(w) * static_cast<size_t>(h), 0);
  // Marks the pixels whose centre lies within r of the segment a-b (r: half the width plus
  // one pixel of anti-aliased edge), by stamping discs every half pixel along it.
  auto stamp = [&](ImVec2 p, ImVec2 q, double r) {
    double ax = p.x, ay = p.y, bx = q.x, by = q.y;
    const PixelRect near{x0 - r, y0 - r, x1 + r, y1 + r};
    if (!clip_segment(ax, ay, bx, by, near)) return;
    const double len = std::hypot(bx - ax, by - ay);
    const int steps = std::max(1, static_cast<int>(std::ceil(len / 0.5)));
    for (int k = 0; k <= steps; ++k) {
      const double t = static_cast<double>(k) / steps;
      const double cx = ax + (bx - ax) * t, cy = ay + (by - ay) * t;
      const int i0 = std::max(0, static_cast<int>(std::floor(cx - r - 0.5)) - px0);
      const int i1 = std::min(w - 1, static_cast<int>(std::ceil(cx + r)) - px0);
      const int j0 = std::max(0, static_cast<int>(std::floor(cy - r - 0.5)) - py0);
      const int j1 = std::min(h - 1, static_cast<int>(std::ceil(cy + r)) - py0);
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          const double dx = px0 + i + 0.5 - cx, dy = py0 + j + 0.5 - cy;
          if (dx * dx + dy * dy <= r * r) hit[static_cast<size_t>(j) * w + i] = 1;
        }
    }
  };
  for (const PlotSeries& s : spec.series) {
    const double m = s.thickness + 2.0;
    const PixelRect clip{a.x0 - m, a.y0 - m, a.x1 + m, a.y1 + m};
    const double r = 0.5 * s.thickness + 1.0;
    for (const auto& line : project_polylines(s.x, s.y, lay.x, lay.y, clip)) {
      if (line.size() == 1) stamp(line[0], line[0], std::max(s.thickness, 2.0f) + 1.0);
      for (size_t i = 1; i < line.size(); ++i) stamp(line[i - 1], line[i], r);
    }
  }
  for (const PlotRefLine& l : spec.ref_lines) {
    const bool vertical = l.axis == LineAxis::x;
    const double px = (vertical ? lay.x : lay.y).to_px(l.at);
    if (std::isnan(px)) continue;
    const ImVec2 from = vertical ? ImVec2(static_cast<float>(px), static_cast<float>(a.y0))
                                 : ImVec2(static_cast<float>(a.x0), static_cast<float>(px));
    const ImVec2 to = vertical ? ImVec2(static_cast<float>(px), static_cast<float>(a.y1))
                               : ImVec2(static_cast<float>(a.x1), static_cast<float>(px));
    stamp(from, to, 0.5 * l.thickness + 1.0);
  }
  size_t n = 0;
  for (unsigned char c : hit) n += c;
  return n;
}

}  // namespace dampbound::ui
