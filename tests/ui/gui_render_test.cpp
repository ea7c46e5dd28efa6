// The whole tuner window rendered headless through the EGL host (Mesa surfaceless on CI): the
// same frame function as the GLFW window, the mesh view's offscreen GL pass included, and the
// export of the plots from inside a frame. PNGs go to $DAMPBOUND_UI_PNG_DIR, else
// ui_test_output/.
#if defined(DAMPBOUND_HAVE_EGL)
#include <gtest/gtest.h>
#include <imgui.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "core/analysis/expect.hpp"
#include "core/io/scene_file.hpp"
#include "dampbound/run/scene.hpp"
#include "tests/test_scenes.hpp"
#include "ui/egl_host.hpp"
#include "ui/gui_app.hpp"
#include "ui/gui_export.hpp"
#include "ui/gui_items.hpp"
#include "ui/image.hpp"
#include "ui/mesh_style.hpp"
#include "ui/settings.hpp"
#include "ui/tuner_plots.hpp"
#include "tests/ui/ui_test_util.hpp"

namespace dampbound::ui {
namespace {

using ui_test::out_path;
using ui_test::headless;

namespace fs = std::filesystem;

GuiOptions demo_options(const fs::path& config) {
  GuiOptions o;
  o.config_dir = config.string();
  o.scenes_dir = DAMPBOUND_SOURCE_DIR "/scenes";
  o.scene = load_scene(DAMPBOUND_SOURCE_DIR "/scenes/paper-plane.toml");
  o.steps_per_frame = 4;
  o.play = true;
  o.demo = true;
  o.scripted = true;
  return o;
}

/// Pixels of `img` inside `r` (window pixels) matching `color` to within `tolerance`.
long count_in(const Image& img, const PanelRect& r, Rgba color, int tolerance) {
  long n = 0;
  for (int y = std::max(0, static_cast<int>(r.y)); y < std::min(img.height, static_cast<int>(r.y + r.h)); ++y)
    for (int x = std::max(0, static_cast<int>(r.x)); x < std::min(img.width, static_cast<int>(r.x + r.w)); ++x) {
      const Rgba p = img.pixel(x, y);
      n += std::abs(p.r - color.r) <= tolerance && std::abs(p.g - color.g) <= tolerance &&
           std::abs(p.b - color.b) <= tolerance;
    }
  return n;
}

/// demo_options() with nothing persisted and no demo pins.
GuiOptions bare_options() {
  GuiOptions o = demo_options(fs::path());
  o.config_dir.clear();
  o.demo = false;
  return o;
}

TEST(GuiRender, ARememberedHostileSceneDoesNotStopTheNextStart) {
  // The settings remembered a scene of 40 000 dotted key parts, which overflowed toml++'s
  // stack: every later start of `gui` crashed. Now the scene is refused with a warning and
  // the window opens on the paper plane.
  const fs::path config = fs::temp_directory_path() / "dampbound_gui_hostile_scene";
  fs::remove_all(config);
  fs::create_directories(config);
  const fs::path bomb = config / "bomb.toml";
  {
    std::ofstream out(bomb);
    out << "a";
    for (int k = 0; k < 40000; ++k) out << ".a";
    out << " = 1\n";
  }
  GuiSettings remembered = default_gui_settings();
  remembered.scene_path = bomb.string();
  save_gui_settings(remembered, (config / "settings.txt").string());
  GuiOptions o = demo_options(config);
  o.scene.reset();
  o.demo = false;
  GuiApp app(o);
  ASSERT_FALSE(app.warnings().empty());
  EXPECT_NE(app.warnings().front().find("more than 64 parts"), std::string::npos)
      << app.warnings().front();
  EXPECT_EQ(app.tuner().session().model().spec().node_count(), 1296);  // the paper plane
  fs::remove_all(config);
}

TEST(GuiRender, WholeWindowHeadless) {
  const fs::path config = fs::temp_directory_path() / "dampbound_gui_render_test";
  fs::remove_all(config);
  EglOptions eo;
  eo.render = gui_render_options();
  EglHost host(eo);
  GuiApp app(demo_options(config));
  ASSERT_EQ(app.tuner().pins().size(), 2u);
  const int frames = 3;
  std::string export_summary;
  const Image img = host.render_frames(
      1280, 800,
      [&](FrameInfo& info) {
        app.frame(info);
        if (info.index == frames - 1) {
          // Export from inside a frame, as the button does.
          Tuner& t = app.tuner();
          export_summary =
              export_runs(t, {tuner_displacement_plot(t, {}), tuner_envelope_plot(t, {})},
                          (config / "export").string(), "test");
        }
      },
      frames);
  EXPECT_EQ(app.tuner().session().state().iteration, frames * 4);
  write_png_atomic(img, out_path("gui_window.png"));
  // 1280 x 800 is compact: five panels, each inside the window (none cut off), no Status.
  EXPECT_FALSE(app.window_rect("Status"));
  std::map<std::string, PanelRect> panel;
  for (const char* name : {"Parameters", "Mesh view", "Damping bounds", "Displacement", "Runs"}) {
    const auto r = app.window_rect(name);
    ASSERT_TRUE(r) << name;
    EXPECT_GE(r->x, 0) << name;
    EXPECT_GE(r->y, 0) << name;
    EXPECT_LE(r->x + r->w, 1280) << name;
    EXPECT_LE(r->y + r->h, 800) << name;
    EXPECT_GT(r->w, 300) << name;
    EXPECT_GT(r->h, 300) << name;
    panel[name] = *r;
  }
  // The mesh view drew its nodes in the "within bounds" colour, inside its own panel (the
  // colour also names the watched node's state in the status).
  EXPECT_GT(count_in(img, panel["Mesh view"], rgba_from_u32(status_color(NodeStatus::within)), 10),
            100);
  // Each pinned run is drawn in its colour on both plots, in their panels.
  for (const Pin& p : app.tuner().pins()) {
    EXPECT_GT(count_in(img, panel["Damping bounds"], rgba_from_u32(p.color), 12), 20) << p.name;
    EXPECT_GT(count_in(img, panel["Displacement"], rgba_from_u32(p.color), 12), 20) << p.name;
  }
  // The export wrote a light figure with both plots (displacement on top, then the
  // envelope), each showing the first pin, and the CSVs.
  EXPECT_NE(export_summary.find("test_plots.png"), std::string::npos);
  const Image fig = read_png((config / "export" / "test_plots.png").string());
  EXPECT_EQ(fig.width, 1400);
  EXPECT_EQ(fig.height, 1000);
  EXPECT_EQ(fig.pixel(2, 2), (Rgba{255, 255, 255, 255}));
  const Rgba pin0 = rgba_from_u32(app.tuner().pins()[0].color);
  EXPECT_GT(count_in(fig, {"top", 0, 0, 1400, 500}, pin0, 12), 50);
  EXPECT_GT(count_in(fig, {"bottom", 0, 500, 1400, 500}, pin0, 12), 50);
  write_png_atomic(fig, out_path("gui_export.png"));
  EXPECT_TRUE(fs::exists(config / "export" / "test_traces.csv"));
  EXPECT_TRUE(fs::exists(config / "export" / "test_runs.csv"));
  // Settings and layout are saved into the config folder.
  app.save();
  app.release_gl();
  EXPECT_TRUE(fs::exists(config / "settings.txt"));
  fs::remove_all(config);
}

TEST(GuiRender, TheFirstFrameOfALaterStartIsNotBlank) {
  // With a remembered layout (imgui.ini), ImGui hides a new window for its first frame unless
  // its size is set by the program: `gui --frames 1 --screenshot` wrote a PNG of the empty
  // background on every start after the first.
  const fs::path config = fs::temp_directory_path() / "dampbound_gui_second_start";
  fs::remove_all(config);
  GuiOptions o = demo_options(config);
  o.demo = false;
  o.play = false;
  for (int start = 0; start < 2; ++start) {
    EglHost host(headless());
    GuiApp app(o);
    const Image img = host.render_frames(
        1280, 800,
        [&](FrameInfo& info) {
          app.frame(info);
          app.save();  // in the frame: the EGL host's ImGui context ends with render_frames
        },
        1);
    EXPECT_FALSE(is_blank(img)) << "start " << start;
    const auto params = app.window_rect("Parameters");
    ASSERT_TRUE(params) << "start " << start;
    EXPECT_EQ(params->x, 0) << "start " << start;
    if (start == 1) write_png_atomic(img, out_path("gui_second_start.png"));
    app.release_gl();
    EXPECT_TRUE(fs::exists(config / "imgui.ini"));
  }
  // A panel the user moved comes back where imgui.ini has it, from the first frame on.
  {
    std::ofstream ini(config / "imgui.ini", std::ios::app);
    ini << "\n[Window][Parameters]\nPos=40,30\nSize=300,500\nCollapsed=0\n";
  }
  EglHost host(headless());
  GuiApp app(o);
  const Image img = host.render_frames(
      1280, 800, [&](FrameInfo& info) { app.frame(info); }, 1);
  EXPECT_FALSE(is_blank(img));
  const auto moved = app.window_rect("Parameters");
  ASSERT_TRUE(moved);
  EXPECT_EQ(moved->x, 40);
  EXPECT_EQ(moved->y, 30);
  EXPECT_EQ(moved->w, 300);
  app.release_gl();
  fs::remove_all(config);
}

TEST(GuiRender, DivergedRunShowsNoNaNAndStops) {
  EglHost host(headless());
  GuiOptions o = bare_options();
  o.overrides = [](Params& p, StopRules&) {
    p.kappa = 1.0;
    p.gamma = 0.0;
  };
  GuiApp app(o);
  const Image img = host.render_frames(1024, 640, app.frame_fn(), 4);
  EXPECT_EQ(app.tuner().session().result().outcome, Outcome::diverged);
  EXPECT_FALSE(app.tuner().playing());
  EXPECT_FALSE(is_blank(img));
  write_png_atomic(img, out_path("gui_diverged.png"));
  app.release_gl();
}

TEST(GuiRender, CriteriaAndSuggestTabs) {
  EglHost host(headless());
  GuiOptions o = bare_options();
  o.overrides = [](Params& p, StopRules&) { p.gamma = 0.001; };
  GuiApp app(o);
  app.select_tab("Criteria");
  app.select_tab("Suggest");  // the last one asked wins: one pending tab at a time
  app.start_suggest();
  app.suggestions().wait();
  ASSERT_TRUE(app.suggestions().result().has_value()) << app.suggestions().error();
  Image img = host.render_frames(1600, 1000, app.frame_fn(), 3);
  EXPECT_FALSE(is_blank(img));
  write_png_atomic(img, out_path("gui_suggest.png"));
  app.select_tab("Criteria");
  img = host.render_frames(1600, 1000, app.frame_fn(), 3);
  EXPECT_FALSE(app.tuner().criteria().empty());
  // Every row at the default window size: the table does not scroll.
  EXPECT_FALSE(app.criteria_rows_hidden());
  write_png_atomic(img, out_path("gui_criteria.png"));
  app.release_gl();
}

// A loaded chain analysed at its static equilibrium: the Criteria tab says where (Newton's
// steps and the net force left), and no rest-state note, which belongs to the analysis at rest.
TEST(GuiRender, CriteriaAtTheStaticEquilibrium) {
  EglHost host(headless());
  GuiOptions o = bare_options();
  SceneSpec chain;
  chain.name = "loaded chain";
  chain.model = test::loaded_chain();
  o.scene = chain;
  GuiApp app(o);
  app.select_tab("Criteria");
  TunerCriteria& c = app.tuner().criteria_state();
  c.set_linearisation(Linearisation::equilibrium);
  host.render_frames(1600, 1000, app.frame_fn(), 1);  // starts the analysis on the worker
  c.wait();
  app.select_tab("Criteria");  // each render starts the window afresh
  const Image img = host.render_frames(1600, 1000, app.frame_fn(), 3);
  EXPECT_FALSE(is_blank(img));
  ASSERT_NE(c.exact_equilibrium(), nullptr) << c.equilibrium_failure();
  EXPECT_EQ(c.rest_net_force(), nullptr);
  write_png_atomic(img, out_path("gui_criteria_equilibrium.png"));
  app.release_gl();
}

// Over the factorisation budget the Suggest tab shows what is proved stable without one.
TEST(GuiRender, SuggestOverTheFactorisationBudget) {
  EglHost host(headless());
  GuiOptions o = bare_options();
  o.factor_budget = 1;  // one flop: nothing is factorised
  GuiApp app(o);
  app.select_tab("Suggest");
  app.start_suggest();
  app.suggestions().wait();
  ASSERT_TRUE(app.suggestions().result().has_value()) << app.suggestions().error();
  EXPECT_TRUE(app.suggestions().result()->damping.proved_only);
  const Image img = host.render_frames(1600, 1000, app.frame_fn(), 3);
  EXPECT_FALSE(is_blank(img));
  write_png_atomic(img, out_path("gui_suggest_over_budget.png"));
  app.release_gl();
}

TEST(GuiRender, PanelsFollowTheWindowSize) {
  EglHost host(headless());
  GuiOptions o = bare_options();
  GuiApp app(o);
  host.render_frames(1280, 800, app.frame_fn(), 2);
  // The user moves and resizes one panel (as a drag would); the others stay where the default
  // layout put them.
  host.render_frames(
      1280, 800,
      [&](FrameInfo& info) {
        app.frame(info);
        if (info.index == 0) {
          ImGui::SetWindowPos("Damping bounds", ImVec2(640, 100));
          ImGui::SetWindowSize("Damping bounds", ImVec2(400, 300));
        }
      },
      2);
  auto moved = app.window_rect("Damping bounds");
  ASSERT_TRUE(moved.has_value());
  EXPECT_FLOAT_EQ(moved->x, 640);
  EXPECT_FLOAT_EQ(moved->w, 400);
  // The window shrinks to 960 x 600 (three quarters): default panels take the default layout
  // of the new size (they fill it), the moved one keeps its place and size in proportion.
  const Image img = host.render_frames(960, 600, app.frame_fn(), 2);
  EXPECT_FALSE(is_blank(img));
  const auto params = app.window_rect("Parameters");
  const auto runs = app.window_rect("Runs");
  moved = app.window_rect("Damping bounds");
  ASSERT_TRUE(params && runs && moved);
  EXPECT_FLOAT_EQ(params->x, 0);
  EXPECT_FLOAT_EQ(params->y, 0);
  EXPECT_FLOAT_EQ(params->w, 330);  // the left column's minimum width
  EXPECT_FLOAT_EQ(params->h, 600);  // compact: the parameters take the whole column
  EXPECT_NEAR(runs->x + runs->w, 960, 1);
  EXPECT_NEAR(runs->y + runs->h, 600, 1);
  EXPECT_FLOAT_EQ(moved->x, 480);
  EXPECT_FLOAT_EQ(moved->y, 75);
  EXPECT_FLOAT_EQ(moved->w, 300);
  EXPECT_FLOAT_EQ(moved->h, 225);
  // And back up: the default panels fill 1600 x 1000.
  host.render_frames(1600, 1000, app.frame_fn(), 2);
  EXPECT_NEAR(app.window_rect("Runs")->x + app.window_rect("Runs")->w, 1600, 1);
  EXPECT_NEAR(app.window_rect("Status")->y + app.window_rect("Status")->h, 1000, 1);
  write_png_atomic(img, out_path("gui_resized.png"));
  app.release_gl();
}

// The Map tab at the smallest supported size: the worker's passes arrive while frames go on,
// and the picture is the map; then Save scene writes a file that check passes.
TEST(GuiRender, MapTabAndSaveScene) {
  EglHost host(headless());
  GuiOptions o = bare_options();
  SceneSpec small = paper_plane_scene(12);
  small.rules.max_iterations = 300;
  o.scene = small;
  GuiApp app(o);
  app.map_view().finest = 16;
  app.select_tab("Map");
  host.render_frames(1024, 640, app.frame_fn(), 2);  // the first frame starts the worker
  app.map().wait();
  const Image img = host.render_frames(1024, 640, app.frame_fn(), 2);
  EXPECT_FALSE(is_blank(img));
  const auto r = app.map().result();
  ASSERT_TRUE(r) << app.map().unsupported();
  EXPECT_TRUE(r->finest);
  EXPECT_EQ(r->cells.size(), 256u);
  write_png_atomic(img, out_path("gui_map.png"));
  app.select_tab("Save scene");
  host.render_frames(1024, 640, app.frame_fn(), 2);
  const std::string path = (fs::temp_directory_path() / "dampbound_gui_saved.toml").string();
  const std::string summary = app.save_scene(path);
  EXPECT_NE(summary.find("saved"), std::string::npos);
  for (const auto& x : check_expectations(load_scene(path))) EXPECT_TRUE(x.pass) << x.what;
  app.release_gl();
}

/// Mouse input for the next frame (the headless host has no platform backend: the frame
/// function sets the ImGui IO that the next NewFrame reads).
void mouse(ImVec2 pos, bool down) {
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = pos;
  io.MouseDown[0] = down;
}

ImVec2 on_screen(GuiApp& app, int node) {
  MeshView& v = app.mesh_view();
  const Viewport& vp = v.viewport();
  const Vec3f p = app.tuner().session().state().x[static_cast<size_t>(node)].cast<float>();
  const ScreenPoint s = project(v.camera().view_projection(vp.aspect()), vp, p);
  return ImVec2(s.x, s.y);
}

TEST(GuiRender, MouseWatchesDragsAndCutsInTheMeshView) {
  EglHost host(headless());
  GuiOptions o = bare_options();
  o.play = false;
  o.scripted = false;
  GuiApp app(o);
  const int watch_node = 100, drag_node = 200;
  // Hovering a node shows its state and bounds.
  const Image hover = host.render_frames(
      1280, 800,
      [&](FrameInfo& info) {
        app.frame(info);
        mouse(on_screen(app, watch_node), false);
      },
      3);
  write_png_atomic(hover, out_path("gui_hover.png"));
  double y_before = 0;
  int watched_after_click = -1;
  ImVec2 cut_from, cut_to;
  host.render_frames(
      1280, 800,
      [&](FrameInfo& info) {
        app.frame(info);
        const ImVec2 a = on_screen(app, watch_node), b = on_screen(app, drag_node);
        switch (info.index) {
          case 0:
            mouse(a, false);
            break;  // hover the node
          case 1:
            mouse(a, true);
            break;  // press
          case 2:
            mouse(a, false);
            break;  // release without moving: a click
          case 3:
            watched_after_click = app.tuner().session().watched();
            y_before = app.tuner().session().state().x[drag_node].y();
            mouse(b, false);
            break;
          case 4:
            mouse(b, true);
            break;
          case 5:
            mouse(ImVec2(b.x, b.y - 20), true);
            break;  // drag upwards on the screen
          case 6:
            mouse(ImVec2(b.x, b.y - 40), true);
            break;
          case 7:
            mouse(ImVec2(b.x, b.y - 40), false);
            break;
          case 8: {
            // The cut tool: a line across the middle of the view.
            app.mesh_view().cut_tool = true;
            const Viewport& vp = app.mesh_view().viewport();
            cut_from = ImVec2(vp.x + vp.w * 0.5f, vp.y + 5);
            cut_to = ImVec2(vp.x + vp.w * 0.5f, vp.y + vp.h - 5);
            mouse(cut_from, false);
            break;
          }
          case 9:
            mouse(cut_from, true);
            break;
          case 10:
            mouse(cut_to, true);
            break;
          case 11:
            mouse(cut_to, false);
            break;
          default:
            break;
        }
      },
      13);
  EXPECT_EQ(watched_after_click, watch_node);
  EXPECT_EQ(app.tuner().session().watched(), drag_node);
  EXPECT_GT(app.tuner().session().state().x[drag_node].y(), y_before + 0.5);  // moved up
  EXPECT_GT(app.tuner().session().springs_cut(), 10);
  EXPECT_EQ(app.tuner().session().state().iteration, 0);  // paused all along
  app.release_gl();
}

// The Worst nodes tab lists the nodes that limit dt; a click on a row watches that node, as a
// click on it in the mesh view does (the plots and the status follow it).
TEST(GuiRender, AClickOnAWorstNodeRowWatchesIt) {
  EglHost host(headless());
  GuiOptions o = bare_options();
  o.scene = load_scene(DAMPBOUND_SOURCE_DIR "/scenes/stiff-region.toml");
  o.play = false;
  o.scripted = false;
  GuiApp app(o);
  app.select_tab("Worst nodes");
  const int watched_before = app.tuner().session().watched();
  item_log().on = true;
  int target = -1, phase = 0;
  ImVec2 at;
  const Image img = host.render_frames(
      1600, 1000,
      [&](FrameInfo& info) {
        app.frame(info);
        item_log().end_frame();
        if (info.layout_pass) return;
        if (target < 0) {  // the third row of the list, by its label "#node"
          int row = 0;
          for (const ItemRecord& r : item_log().last())
            if (r.kind == ItemKind::selectable && r.window.rfind("Runs", 0) == 0 &&
                r.label[0] == '#' &&
                ++row == 3) {
              target = std::stoi(r.label.substr(1));
              at = ImVec2(0.5f * (r.min.x + r.max.x), 0.5f * (r.min.y + r.max.y));
            }
          mouse(at, false);
          return;
        }
        mouse(at, ++phase == 1);  // hovered, then pressed for a frame, then released
      },
      10);
  item_log().on = false;
  write_png_atomic(img, out_path("gui_worst.png"));
  ASSERT_GE(target, 0) << "no row drawn";
  EXPECT_NE(target, watched_before);
  EXPECT_EQ(app.tuner().session().watched(), target);
  app.release_gl();
}

// xdotool's "mousemove X Y click 1" arrives as one frame: the pointer jumps onto a node and the
// button goes down in the same frame, up in the next. The jump is no drag: the node stays
// where it was (it moved by the jump and followed the pointer) and is watched.
TEST(GuiRender, AnInstantClickAfterAJumpWatchesTheNodeAndLeavesItInPlace) {
  EglHost host(headless());
  GuiOptions o = bare_options();
  o.play = false;
  o.scripted = false;
  GuiApp app(o);
  const int node = 100;
  Vec3 before, after_click, after_move;
  host.render_frames(
      1280, 800,
      [&](FrameInfo& info) {
        app.frame(info);
        const Viewport& vp = app.mesh_view().viewport();
        const ImVec2 away(vp.x + vp.w - 4, vp.y + vp.h - 4);
        switch (info.index) {
          case 0:
            mouse(away, false);
            break;
          case 1:
            before = app.tuner().session().state().x[node];
            mouse(on_screen(app, node), true);  // the jump and the press in one frame
            break;
          case 2:
            mouse(on_screen(app, node), false);
            break;
          case 3:
            after_click = app.tuner().session().state().x[node];
            mouse(away, false);  // the pointer leaves without a button
            break;
          case 5:
            after_move = app.tuner().session().state().x[node];
            break;
          default:
            break;
        }
      },
      6);
  EXPECT_EQ(app.tuner().session().watched(), node);
  EXPECT_EQ((after_click - before).norm(), 0.0) << "the jump moved the node";
  EXPECT_EQ((after_move - before).norm(), 0.0) << "the node followed the pointer";
  app.release_gl();
}

}  // namespace
}  // namespace dampbound::ui
#endif
