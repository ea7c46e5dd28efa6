#include "core/io/vtu.hpp"

#include "core/physics/safe_bound.hpp"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>

#include "core/io/files.hpp"
#include "core/io/format.hpp"
#include "core/physics/damping_ratio.hpp"
#include "core/physics/safe_bound.hpp"
#include "core/physics/safe_bound_nodes.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {
namespace {

/// Base64 (RFC 4648) of a byte block.
std::string base64(const std::vector<unsigned char>& in) {
  static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  for (size_t i = 0; i < in.size(); i += 3) {
    const unsigned b0 = in[i], b1 = i + 1 < in.size() ? in[i + 1] : 0u,
                   b2 = i + 2 < in.size() ? in[i + 2] : 0u;
    out += abc[b0 >> 2];
    out += abc[((b0 & 3u) << 4) | (b1 >> 4)];
    out += i + 1 < in.size() ? abc[((b1 & 15u) << 2) | (b2 >> 6)] : '=';
    out += i + 2 < in.size() ? abc[b2 & 63u] : '=';
  }
  return out;
}

/// A VTK binary DataArray: a UInt64 byte count, then the values, all base64-encoded together.
template <class T>
void data_array(std::ostream& out, const char* type, const char* name, int components,
                const std::vector<T>& values) {
  const std::uint64_t bytes = values.size() * sizeof(T);
  std::vector<unsigned char> raw(sizeof bytes + bytes);
  std::memcpy(raw.data(), &bytes, sizeof bytes);
  if (bytes) std::memcpy(raw.data() + sizeof bytes, values.data(), bytes);
  out << "        <DataArray type=\"" << type << "\" Name=\"" << name << "\" NumberOfComponents=\""
      << components << "\" format=\"binary\">\n          " << base64(raw)
      << "\n        </DataArray>\n";
}

std::vector<double> flatten(const std::vector<Vec3>& v) {
  std::vector<double> out;
  out.reserve(3 * v.size());
  for (const Vec3& x : v) out.insert(out.end(), {x.x(), x.y(), x.z()});
  return out;
}

/// The run's parameters as FieldData, one tuple each; the names in a comment beside them.
void write_parameters(std::ostream& out, const Params& p) {
  out << "    <!-- dampbound parameters: policy=" << to_string(p.policy)
      << " integrator=" << to_string(p.integrator) << " -->\n    <FieldData>\n";
  const std::pair<const char*, double> values[] = {
      {"m", p.m},   {"kappa", p.kappa},   {"gamma", p.gamma},
      {"dt", p.dt}, {"factor", p.factor}, {"kd", p.kd},
      {"rayleigh_mass", p.rayleigh_mass}, {"rayleigh_stiffness", p.rayleigh_stiffness}};
  for (const auto& [name, value] : values)
    out << "      <DataArray type=\"Float64\" Name=\"" << name
        << "\" NumberOfTuples=\"1\" format=\"ascii\">" << format_number(value)
        << "</DataArray>\n";
  out << "    </FieldData>\n";
}

}  // namespace

std::vector<std::string> pvd_step_files(const std::string& text) {
  std::vector<std::string> out;
  const std::string key = "file=\"";
  for (size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + 1)) {
    const size_t start = at + key.size(), end = text.find('"', start);
    if (end == std::string::npos) break;
    const std::string name = text.substr(start, end - start);
    // Only a name this class writes: step_, digits, .vtu; no folder, nothing else.
    const size_t digits = name.size() >= 10 ? name.size() - 9 : 0;
    bool ours = digits > 0 && name.rfind("step_", 0) == 0 &&
                name.compare(name.size() - 4, 4, ".vtu") == 0;
    for (size_t k = 5; ours && k < 5 + digits; ++k)
      ours = name[k] >= '0' && name[k] <= '9';
    if (ours) out.push_back(name);
  }
  return out;
}

int state_code(NodeStatus s) {
  return static_cast<int>(s);
}

void write_vtu(std::ostream& out, const Model& model, const State& state, const StepWorkspace& ws,
               double dt, const std::vector<BodyCell>& body, const PointArrays& extra,
               const Params* params) {
  const size_t n = model.spec().rest.size(), ns = model.spec().springs.size();
  const bool stepped = ws.status.size() == n;  // else iteration 0: no step has run yet
  std::vector<Vec3> disp(n);
  std::vector<double> upper(n), gamma(n), safe = stepped ? ws.safe_bound : std::vector<double>(n);
  if (!stepped) {  // SPEC 9 at the initial state, as step() would evaluate it
    std::vector<double> row_sum;
    safe_row_sums(model, state.x, row_sum);
    for (size_t i = 0; i < n; ++i)
      safe[i] = model.spec().fixed[i] ? std::numeric_limits<double>::infinity()
                               : safe_gamma(model.mass[i], dt, row_sum[i]);
  }
  std::vector<std::int32_t> code(n);
  for (size_t i = 0; i < n; ++i) {
    disp[i] = state.x[i] - model.spec().rest[i];
    upper[i] = stepped ? ws.upper_bound[i] : std::numeric_limits<double>::infinity();
    gamma[i] = stepped ? ws.gamma_eff[i] : (model.spec().fixed[i] ? 0.0 : model.gamma[i]);
    code[i] = state_code(stepped          ? ws.status[i]
                         : model.spec().fixed[i] ? NodeStatus::fixed
                                          : NodeStatus::within);
  }
  std::vector<std::int64_t> conn, offsets;
  std::vector<std::uint8_t> types(ns, 3);  // VTK_LINE
  std::vector<double> kappa(ns), strain(ns);
  std::vector<std::int32_t> spring(ns);
  for (size_t k = 0; k < ns; ++k) {
    const Spring& s = model.spec().springs[k];
    conn.insert(conn.end(), {s.i, s.j});
    offsets.push_back(static_cast<std::int64_t>(conn.size()));
    kappa[k] = model.spring_kappa[k];
    const double l = (state.x[size_t(s.j)] - state.x[size_t(s.i)]).norm();
    strain[k] = s.rest_length > 0 ? (l - s.rest_length) / s.rest_length : 0.0;
    spring[k] = static_cast<std::int32_t>(k);
  }
  for (const BodyCell& c : body) {
    conn.insert(conn.end(), c.corners.begin(), c.corners.end());
    offsets.push_back(static_cast<std::int64_t>(conn.size()));
    types.push_back(c.dimension == 3 ? 10 : c.corners.size() == 3 ? 5 : c.corners.size() == 4 ? 9 : 7);
    kappa.push_back(std::numeric_limits<double>::quiet_NaN());
    strain.push_back(std::numeric_limits<double>::quiet_NaN());
    spring.push_back(-1);
  }
  const size_t cells = types.size();
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n  <UnstructuredGrid>\n";
  if (params != nullptr) write_parameters(out, *params);
  out << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << cells << "\">\n"
      << "      <PointData>\n";
  data_array(out, "Float64", "displacement", 3, flatten(disp));
  data_array(out, "Float64", "velocity", 3, flatten(state.v));
  data_array(out, "Float64", "lower", 1, model.lower_bound);
  data_array(out, "Float64", "upper", 1, upper);
  data_array(out, "Float64", "effective_damping", 1, gamma);
  data_array(out, "Float64", "safe", 1, safe);
  data_array(out, "Int32", "state", 1, code);
  {  // SPEC 9 node by node and the damping ratio (SPEC 10) of the user's gamma_i
    std::vector<double> dt_safe, gamma_safe;
    safe_bounds_per_node(model, state.x, dt, dt_safe, gamma_safe);
    data_array(out, "Float64", "dt_safe", 1, dt_safe);
    data_array(out, "Float64", "gamma_safe", 1, gamma_safe);
    data_array(out, "Float64", "zeta", 1, damping_ratio(model));
  }
  for (const auto& [name, values] : extra) {
    if (values.size() != n) throw std::invalid_argument("write_vtu: array " + name + " is not per node");
    data_array(out, "Float64", name.c_str(), 1, values);
  }
  out << "      </PointData>\n      <CellData>\n";
  data_array(out, "Float64", "stiffness", 1, kappa);
  data_array(out, "Float64", "strain", 1, strain);
  data_array(out, "Int32", "spring", 1, spring);
  out << "      </CellData>\n      <Points>\n";
  data_array(out, "Float64", "Points", 3, flatten(state.x));
  out << "      </Points>\n      <Cells>\n";
  data_array(out, "Int64", "connectivity", 1, conn);
  data_array(out, "Int64", "offsets", 1, offsets);
  data_array(out, "UInt8", "types", 1, types);
  out << "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
}

VtuSeries::VtuSeries(std::string dir, std::vector<BodyCell> body)
    : dir_(std::move(dir)), body_(std::move(body)) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec || !std::filesystem::is_directory(dir_))
    throw InputError(dir_ + ": cannot create the output folder");
  check_writable(dir_ + "/series.pvd");
  std::ifstream old(dir_ + "/series.pvd", std::ios::binary);
  if (old) {
    std::ostringstream text;
    text << old.rdbuf();
    older_ = pvd_step_files(text.str());
  }
}

void VtuSeries::add(const Model& model, const State& state, const StepWorkspace& ws, double dt) {
  char name[32];
  std::snprintf(name, sizeof name, "step_%06d.vtu", state.iteration);
  write_file_atomic(dir_ + "/" + name,
                    [&](std::ostream& out) {
                      write_vtu(out, model, state, ws, dt, body_, has_params_ ? &params_ : nullptr);
                    });
  files_.emplace_back(state.time, name);
}

void VtuSeries::write_collection() const {
  write_file_atomic(dir_ + "/series.pvd", [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
           "  <Collection>\n";
    for (const auto& [t, file] : files_)
      out << "    <DataSet timestep=\"" << format_number(t) << "\" file=\"" << file << "\"/>\n";
    out << "  </Collection>\n</VTKFile>\n";
  });
  // The older series' step files that this one did not write again go: the folder then
  // holds one series, the one series.pvd lists.
  for (const std::string& name : older_) {
    bool kept = false;
    for (const auto& f : files_) kept = kept || f.second == name;
    std::error_code ec;
    if (!kept) std::filesystem::remove(dir_ + "/" + name, ec);
  }
}

}  // namespace dampbound
