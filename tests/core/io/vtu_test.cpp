// ParaView output (core/io/vtu.hpp): the arrays a .vtu holds, read back from the XML the way
// meshio and ParaView read them (base64 of a UInt64 byte count then the values), and the .pvd
// collection.
#include "core/io/vtu.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/io/files.hpp"
#include "core/physics/safe_bound.hpp"

namespace dampbound {
namespace {

const double kInf = std::numeric_limits<double>::infinity();

std::vector<unsigned char> unbase64(const std::string& s) {
  const std::string abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> out;
  unsigned bits = 0;
  int count = 0;
  for (char c : s) {
    if (c == '=') break;
    const size_t v = abc.find(c);
    EXPECT_NE(v, std::string::npos) << "not base64: " << c;
    bits = (bits << 6) | static_cast<unsigned>(v);
    count += 6;
    if (count >= 8) {
      count -= 8;
      out.push_back(static_cast<unsigned char>((bits >> count) & 0xffu));
    }
  }
  return out;
}

/// The values of the DataArray named `name`, checking its byte-count header and its type.
template <class T>
std::vector<T> array_of(const std::string& xml, const std::string& name, const std::string& type,
                        int components) {
  const std::string open = "type=\"" + type + "\" Name=\"" + name + "\" NumberOfComponents=\"" +
                           std::to_string(components) + "\" format=\"binary\">";
  const size_t at = xml.find(open);
  if (at == std::string::npos) {
    ADD_FAILURE() << "no array " << name;
    return {};
  }
  const size_t from = xml.find_first_not_of(" \n", at + open.size());
  const std::string text = xml.substr(from, xml.find('<', from) - from);
  const std::vector<unsigned char> raw = unbase64(text.substr(0, text.find_last_not_of(" \n") + 1));
  std::uint64_t bytes = 0;
  std::memcpy(&bytes, raw.data(), sizeof bytes);
  EXPECT_EQ(bytes + 8, raw.size()) << name;
  std::vector<T> out(bytes / sizeof(T));
  std::memcpy(out.data(), raw.data() + 8, bytes);
  return out;
}

Params two_node_params() {
  Params p;
  p.m = 0.001, p.kappa = 0.001, p.gamma = 0.002, p.dt = 0.05;
  return p;
}

Model two_node_model() {
  ModelSpec spec;
  add_node(spec, Vec3(0, 0, 0));
  add_node(spec, Vec3(1, 0, 0));
  add_spring(spec, 0, 1);
  spec.fixed[0] = 1;
  return compile_model(spec, two_node_params());
}

struct TwoNodes {
  Params params = two_node_params();
  Model model = two_node_model();
  State state;
  TwoNodes() {
    state = rest_state(model);
    state.x[1] = Vec3(1.5, 0, 0.25);
    state.v[1] = Vec3(0.1, -0.2, 0);
  }
};

TEST(Vtu, ArraysAtIterationZero) {
  const TwoNodes t;
  std::ostringstream out;
  write_vtu(out, t.model, t.state, StepWorkspace{}, t.params.dt);
  const std::string xml = out.str();
  EXPECT_EQ(xml.substr(0, 22), "<?xml version=\"1.0\"?>\n");
  EXPECT_NE(xml.find("header_type=\"UInt64\""), std::string::npos);
  EXPECT_NE(xml.find("<Piece NumberOfPoints=\"2\" NumberOfCells=\"1\">"), std::string::npos);
  EXPECT_EQ(array_of<double>(xml, "displacement", "Float64", 3),
            (std::vector<double>{0, 0, 0, 0.5, 0, 0.25}));
  EXPECT_EQ(array_of<double>(xml, "velocity", "Float64", 3),
            (std::vector<double>{0, 0, 0, 0.1, -0.2, 0}));
  EXPECT_EQ(array_of<double>(xml, "Points", "Float64", 3),
            (std::vector<double>{0, 0, 0, 1.5, 0, 0.25}));
  EXPECT_EQ(array_of<double>(xml, "lower", "Float64", 1), t.model.lower_bound);
  EXPECT_DOUBLE_EQ(t.model.lower_bound[1], 2 * std::sqrt(0.001 * 0.001));
  EXPECT_EQ(array_of<double>(xml, "upper", "Float64", 1), (std::vector<double>{kInf, kInf}));
  EXPECT_EQ(array_of<double>(xml, "effective_damping", "Float64", 1),
            (std::vector<double>{0, 0.002}));
  EXPECT_EQ(array_of<std::int32_t>(xml, "state", "Int32", 1), (std::vector<std::int32_t>{4, 0}));
  std::vector<double> rows;
  safe_row_sums(t.model, t.state.x, rows);
  const auto safe = array_of<double>(xml, "safe", "Float64", 1);
  ASSERT_EQ(safe.size(), 2u);
  EXPECT_EQ(safe[0], kInf);
  EXPECT_EQ(safe[1], safe_gamma(t.model.mass[1], t.params.dt, rows[1]));
  EXPECT_EQ(array_of<double>(xml, "stiffness", "Float64", 1), (std::vector<double>{0.001}));
  const auto strain = array_of<double>(xml, "strain", "Float64", 1);
  ASSERT_EQ(strain.size(), 1u);
  EXPECT_DOUBLE_EQ(strain[0], std::sqrt(1.5 * 1.5 + 0.25 * 0.25) - 1.0);  // l0 = 1
  EXPECT_EQ(array_of<std::int64_t>(xml, "connectivity", "Int64", 1),
            (std::vector<std::int64_t>{0, 1}));
  EXPECT_EQ(array_of<std::int64_t>(xml, "offsets", "Int64", 1), (std::vector<std::int64_t>{2}));
  EXPECT_EQ(array_of<std::uint8_t>(xml, "types", "UInt8", 1), (std::vector<std::uint8_t>{3}));
}

TEST(Vtu, AfterAStepTheWorkspaceValues) {
  TwoNodes t;
  StepWorkspace ws;
  step(t.model, t.params, t.state, ws);
  std::ostringstream out;
  write_vtu(out, t.model, t.state, ws, t.params.dt);
  const std::string xml = out.str();
  EXPECT_EQ(array_of<double>(xml, "upper", "Float64", 1), ws.upper_bound);
  EXPECT_EQ(array_of<double>(xml, "effective_damping", "Float64", 1), ws.gamma_eff);
  EXPECT_EQ(array_of<double>(xml, "safe", "Float64", 1), ws.safe_bound);
  const auto state = array_of<std::int32_t>(xml, "state", "Int32", 1);
  ASSERT_EQ(state.size(), 2u);
  EXPECT_EQ(state[0], state_code(ws.status[0]));
  EXPECT_EQ(state[0], 4);
  EXPECT_EQ(state[1], state_code(ws.status[1]));
}

TEST(Vtu, StateCodesFollowNodeStatus) {
  EXPECT_EQ(state_code(NodeStatus::within), 0);
  EXPECT_EQ(state_code(NodeStatus::clamped), 1);
  EXPECT_EQ(state_code(NodeStatus::violating), 2);
  EXPECT_EQ(state_code(NodeStatus::unstabilisable), 3);
  EXPECT_EQ(state_code(NodeStatus::fixed), 4);
}

TEST(Vtu, ExtraPointArraysFollowTheOthers) {
  TwoNodes t;
  StepWorkspace ws;
  std::ostringstream out;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  write_vtu(out, t.model, t.state, ws, t.params.dt, {}, {{"contact_stiffness_max", {nan, 1.5}}});
  const std::vector<double> k = array_of<double>(out.str(), "contact_stiffness_max", "Float64", 1);
  ASSERT_EQ(k.size(), 2u);
  EXPECT_TRUE(std::isnan(k[0]));
  EXPECT_EQ(k[1], 1.5);
  EXPECT_LT(out.str().find("Name=\"zeta\""), out.str().find("Name=\"contact_stiffness_max\""));
  std::ostringstream bad;
  EXPECT_THROW(write_vtu(bad, t.model, t.state, ws, t.params.dt, {}, {{"short", {1.0}}}),
               std::invalid_argument);
}

TEST(Vtu, SeriesFilesAndCollection) {
  const std::string dir = ::testing::TempDir() + "vtu_series_test/sub";
  std::filesystem::remove_all(dir);
  TwoNodes t;
  VtuSeries series(dir);
  EXPECT_TRUE(std::filesystem::is_directory(dir));
  series.add(t.model, t.state, StepWorkspace{}, t.params.dt);
  t.state.iteration = 12, t.state.time = 0.6;
  series.add(t.model, t.state, StepWorkspace{}, t.params.dt);
  series.write_collection();
  ASSERT_EQ(series.files().size(), 2u);
  EXPECT_EQ(series.files()[1], std::make_pair(0.6, std::string("step_000012.vtu")));
  EXPECT_TRUE(std::filesystem::exists(dir + "/step_000000.vtu"));
  EXPECT_EQ(read_file_text(dir + "/series.pvd"),
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
            "  <Collection>\n"
            "    <DataSet timestep=\"0\" file=\"step_000000.vtu\"/>\n"
            "    <DataSet timestep=\"0.6\" file=\"step_000012.vtu\"/>\n"
            "  </Collection>\n</VTKFile>\n");
}

TEST(Vtu, ARerunIntoTheFolderLeavesOneSeries) {
  // A first run saves steps 0, 5 and 10; a second, shorter one steps 0 and 3: the folder then
  // holds the second series only, and a file the series never wrote stays.
  const std::string dir = ::testing::TempDir() + "vtu_rerun_test";
  std::filesystem::remove_all(dir);
  TwoNodes t;
  {
    VtuSeries first(dir);
    for (int it : {0, 5, 10}) {
      t.state.iteration = it;
      first.add(t.model, t.state, StepWorkspace{}, t.params.dt);
    }
    first.write_collection();
  }
  std::filesystem::create_directories(dir);
  { std::ofstream(dir + "/notes.vtu") << "mine"; }
  VtuSeries second(dir);
  for (int it : {0, 3}) {
    t.state.iteration = it;
    second.add(t.model, t.state, StepWorkspace{}, t.params.dt);
  }
  second.write_collection();
  EXPECT_TRUE(std::filesystem::exists(dir + "/step_000000.vtu"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/step_000003.vtu"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/step_000005.vtu"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/step_000010.vtu"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/notes.vtu"));
}

TEST(Vtu, PvdStepFilesAreOnlyTheSeriesOwnNames) {
  EXPECT_EQ(pvd_step_files("<DataSet file=\"step_000001.vtu\"/><DataSet file=\"../x.vtu\"/>"
                           "<DataSet file=\"step_1/../../a.vtu\"/><DataSet file=\"step_12.vtu\"/>"),
            (std::vector<std::string>{"step_000001.vtu", "step_12.vtu"}));
}

TEST(Vtu, TheParametersOfTheRunAreFieldData) {
  TwoNodes t;
  Params p = t.params;
  p.kd = 0.25, p.rayleigh_mass = 0.5, p.rayleigh_stiffness = 0.125;
  std::ostringstream os;
  write_vtu(os, t.model, t.state, StepWorkspace{}, p.dt, {}, &p);
  const std::string x = os.str();
  for (const char* s : {"Name=\"kd\" NumberOfTuples=\"1\" format=\"ascii\">0.25<",
                        "Name=\"rayleigh_mass\" NumberOfTuples=\"1\" format=\"ascii\">0.5<",
                        "Name=\"rayleigh_stiffness\" NumberOfTuples=\"1\" format=\"ascii\">0.125<",
                        "Name=\"dt\"", "Name=\"gamma\"", "policy=", "integrator="})
    EXPECT_NE(x.find(s), std::string::npos) << s;
  EXPECT_LT(x.find("<FieldData>"), x.find("<Piece"));
}

}  // namespace
}  // namespace dampbound
