#include "core/sweep/csv.hpp"

#include <algorithm>
#include <cerrno>
#include <cinttypes>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>

#include "core/io/files.hpp"
#include "core/io/format.hpp"
#include "core/sweep/csv_rows.hpp"
#include "core/sweep/journal.hpp"
#include "core/sweep/summary.hpp"
#include "dampbound/physics/bounds.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {

namespace {

constexpr const char* kMagic = "# dampbound sweep v1";

/// A final verdict of `rule` by its name; nullopt for any other text.
std::optional<Outcome> parse_outcome(const std::string& s, StopRule rule) {
  for (Outcome c : final_outcomes(rule))
    if (s == to_string(c)) return c;
  return std::nullopt;
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  size_t start = 0;
  for (;;) {
    const size_t p = line.find(sep, start);
    out.push_back(line.substr(start, p == std::string::npos ? std::string::npos : p - start));
    if (p == std::string::npos) break;
    start = p + 1;
  }
  return out;
}

}  // namespace

std::string fnv1a_hex(const std::string& bytes) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char buf[17];
  c_snprintf(buf, sizeof buf, "%016" PRIx64, h);
  return buf;
}

std::string sweep_csv_columns(StopRule rule, bool damping) {
  std::string c = "trial,m,kappa,gamma,zeta,dt,policy,factor,";
  if (damping) c += "kd,rayleigh_mass,rayleigh_stiffness,";
  c += "class,ran,outcome,iterations,max_displacement,violations,unstabilisable,clamped,"
       "zero_length_springs";
  if (rule == StopRule::settled) c += ",first_entry,left_at,settled_at";
  return c;
}

void write_sweep_header(std::FILE* out, const SweepHeader& h) {
  std::fprintf(out, "%s\n", kMagic);
  std::fprintf(out, "# sweep-id: %s\n", h.sweep_id.c_str());
  std::fprintf(out, "# scene: %s\n", h.scene_path.c_str());
  std::fprintf(out, "# scene-name: %s\n", h.scene_name.c_str());
  std::fprintf(out, "# definition: %s\n", h.definition.c_str());
  std::fprintf(out, "# trials: %" PRIu64 "\n", h.trials);
  std::fprintf(out, "# classes: %" PRIu64 "\n", h.classes);
  std::fprintf(out, "# similarity: %s\n", h.similarity.c_str());
  std::fprintf(out, "# shard: %d/%d\n", h.shard, h.shards);
  std::fprintf(out,
               "# units: m mass unit, kappa mass unit/s^2, gamma mass unit/s, dt s, "
               "max_displacement cm; zeta = gamma/(2 sqrt(m kappa)); counts are node-steps; "
               "ran = 1 for the trial that was stepped, 0 for one that took its class's result "
               "(similarity)%s%s\n",
               h.damping ? "; kd mass unit/s, rayleigh_mass 1/s, rayleigh_stiffness s"
                         : "",
               h.rule == StopRule::settled
                   ? "; outcome by the settled rule: first_entry, left_at, settled_at "
                     "are iterations, 0 = none"
                   : "");
  std::fprintf(out, "%s\n", sweep_csv_columns(h.rule, h.damping).c_str());
}

void for_each_sweep_row(const SweepGrid& grid, const TrialClasses& classes,
                        const std::vector<TrialResult>& class_results, int shard, int shards,
                        const SweepRowVisitor& visit) {
  const SweepSpec& s = grid.spec();
  auto values = [](const Axis& a) {
    std::vector<double> v;
    for (const Decimal& d : a.values) v.push_back(d.value());
    return v;
  };
  const auto mv = values(s.m), kv = values(s.kappa), gv = values(s.gamma), dv = values(s.dt),
             fv = values(s.factor), kdv = values(s.kd), av = values(s.rayleigh_mass),
             bv = values(s.rayleigh_stiffness);
  for (std::uint64_t t = 0; t < grid.trials(); ++t) {
    const std::uint32_t c = classes.class_of[t];
    if (static_cast<int>(c % static_cast<std::uint32_t>(shards)) != shard - 1) continue;
    const SweepGrid::Index ix = grid.index(t);
    SweepRow r;
    r.trial = t;
    r.m = mv[ix.m];
    r.kappa = kv[ix.kappa];
    const double lo = lower_bound(r.m, r.kappa);
    if (s.gamma_mode == GammaMode::zeta) {
      r.zeta = gv[ix.gamma];
      r.gamma = r.zeta * lo;
    } else {
      r.gamma = gv[ix.gamma];
      r.zeta = r.gamma / lo;
    }
    r.dt = dv[ix.dt];
    r.factor = fv[ix.factor];
    if (!kdv.empty()) r.kd = kdv[ix.kd];
    if (!av.empty()) r.rayleigh_mass = av[ix.rayleigh_mass];
    if (!bv.empty()) r.rayleigh_stiffness = bv[ix.rayleigh_stiffness];
    const TrialResult& res = class_results[c];
    r.outcome = res.outcome;
    r.iterations = res.iterations;
    r.max_displacement = res.max_displacement;
    r.unstabilisable = res.unstabilisable;
    r.first_entry = res.first_entry;
    r.left_at = res.left_at;
    r.settled_at = res.settled_at;
    visit(r, ix, c, res);
  }
}

void write_sweep_rows(std::FILE* out, const SweepGrid& grid, const TrialClasses& classes,
                      const std::vector<TrialResult>& class_results, int shard, int shards) {
  const SweepSpec& s = grid.spec();
  auto texts = [](const Axis& a) {
    std::vector<std::string> t;
    for (const Decimal& d : a.values) t.push_back(d.text());
    return t;
  };
  // The axis values as given; gamma in zeta mode and zeta otherwise are computed.
  const auto mt = texts(s.m), kt = texts(s.kappa), gt = texts(s.gamma), dtt = texts(s.dt),
             ft = texts(s.factor), kdt = texts(s.kd), at = texts(s.rayleigh_mass),
             bt = texts(s.rayleigh_stiffness);
  const bool damping = s.has_damping_axes();
  // An axis that is not swept holds the scene's value; a swept sweep's CSV says 0 for none.
  const bool zeta_mode = s.gamma_mode == GammaMode::zeta;
  const char* policy = to_string(s.policy);
  std::string line;
  for_each_sweep_row(grid, classes, class_results, shard, shards,
                     [&](const SweepRow& row, const SweepGrid::Index& ix, std::uint32_t c,
                         const TrialResult& r) {
    char head[64];
    c_snprintf(head, sizeof head, "%" PRIu64 ",", row.trial);
    line = head;
    line += mt[ix.m] + ',' + kt[ix.kappa] + ',' + format_number(row.gamma) + ',';
    line += zeta_mode ? gt[ix.gamma] : format_number(row.zeta);
    line += ',' + dtt[ix.dt] + ',' + policy + ',' + ft[ix.factor] + ',';
    if (damping) {
      line += (kdt.empty() ? std::string("0") : kdt[ix.kd]) + ',';
      line += (at.empty() ? std::string("0") : at[ix.rayleigh_mass]) + ',';
      line += (bt.empty() ? std::string("0") : bt[ix.rayleigh_stiffness]) + ',';
    }
    char tail[200];
    c_snprintf(tail, sizeof tail, "%" PRIu32 ",%d,%s,%d,", c,
                  classes.representative[c] == row.trial ? 1 : 0,
                  to_string(r.outcome), r.iterations);
    line += tail;
    line += format_number(r.max_displacement);
    c_snprintf(tail, sizeof tail, ",%lld,%lld,%lld,%lld", r.violations, r.unstabilisable,
                  r.clamped, r.zero_length_springs);
    line += tail;
    if (s.rules.rule == StopRule::settled) {
      c_snprintf(tail, sizeof tail, ",%d,%d,%d", r.first_entry, r.left_at, r.settled_at);
      line += tail;
    }
    line += '\n';
    std::fwrite(line.data(), 1, line.size(), out);
  });
}

SweepTable read_sweep_csv(const std::string& path, bool keep_lines) {
  check_regular_input(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read the file");
  SweepTable t;
  std::string line;
  int lineno = 0;
  auto fail = [&](const std::string& msg) {
    throw InputError(path + ":" + std::to_string(lineno) + ": " + msg);
  };
  bool magic = false, columns = false;
  while (std::getline(in, line)) {
    ++lineno;
    if (!columns) {
      if (lineno == 1) {
        if (line != kMagic)
          fail("not a dampbound sweep CSV (first line is not '" + std::string(kMagic) + "')");
        magic = true;
        continue;
      }
      if (line.rfind("# ", 0) == 0) {
        const size_t colon = line.find(": ");
        if (colon == std::string::npos) continue;
        const std::string key = line.substr(2, colon - 2), value = line.substr(colon + 2);
        SweepHeader& h = t.header;
        if (key == "sweep-id")
          h.sweep_id = value;
        else if (key == "scene")
          h.scene_path = value;
        else if (key == "scene-name")
          h.scene_name = value;
        else if (key == "definition") {
          h.definition = value;
          if (const auto p = definition_value(value, "policy")) h.policy = parse_policy(*p);
        }
        else if (key == "trials" || key == "classes") {
          // A sweep has at most 2^32 classes (class indices are 32 bits), and so many trials.
          char* end = nullptr;
          errno = 0;
          const unsigned long long n = std::strtoull(value.c_str(), &end, 10);
          if (value.empty() || value[0] == '-' || *end || errno || n > (1ull << 32))
            fail("bad " + key + " count (a whole number up to 2^32)");
          (key == "trials" ? h.trials : h.classes) = n;
        } else if (key == "similarity")
          h.similarity = value;
        else if (key == "shard") {
          char extra = 0;
          if (std::sscanf(value.c_str(), "%9d/%9d%c", &h.shard, &h.shards, &extra) != 2 ||
              h.shards < 1 || h.shard < 1 || h.shard > h.shards)
            fail("bad shard line (K/N with 1 <= K <= N < 1e9)");
        }
        continue;
      }
      bool known = false;
      for (StopRule rule : {StopRule::first_entry, StopRule::settled})
        for (bool damping : {false, true})
          if (line == sweep_csv_columns(rule, damping)) {
            t.header.rule = rule;
            t.header.damping = damping;
            known = true;
          }
      if (!known) fail("unexpected column line (not a sweep CSV of this dampbound version)");
      columns = true;
      continue;
    }
    if (line.empty()) continue;
    const std::vector<std::string> f = split(line, ',');
    const size_t extra = t.header.damping ? 3 : 0;  // kd, rayleigh_mass, rayleigh_stiffness
    const size_t fields = (t.header.rule == StopRule::settled ? 20 : 17) + extra;
    if (f.size() != fields)
      fail("expected " + std::to_string(fields) + " fields, got " + std::to_string(f.size()));
    SweepRow r;
    char* end = nullptr;
    r.trial = std::strtoull(f[0].c_str(), &end, 10);
    if (f[0].empty() || *end) fail("bad trial index '" + printable(f[0]) + "'");
    // Every number whole, or the line is refused (a field such as "abc" once read as 0).
    auto number = [&](size_t k, const char* column) {
      char* stop = nullptr;
      const double v = c_strtod(f[k].c_str(), &stop);
      if (f[k].empty() || *stop) fail("bad number '" + printable(f[k]) + "' in column " + column);
      return v;
    };
    auto integer = [&](size_t k, const char* column, long long lo, long long hi) {
      char* stop = nullptr;
      errno = 0;
      const long long v = std::strtoll(f[k].c_str(), &stop, 10);
      if (f[k].empty() || *stop || errno == ERANGE || v < lo || v > hi)
        fail("bad integer '" + printable(f[k]) + "' in column " + column);
      return v;
    };
    const long long kInt = 2147483647;  // the int columns
    r.m = number(1, "m");
    r.kappa = number(2, "kappa");
    r.gamma = number(3, "gamma");
    r.zeta = number(4, "zeta");
    r.dt = number(5, "dt");
    r.factor = number(7, "factor");
    if (t.header.damping) {
      r.kd = number(8, "kd");
      r.rayleigh_mass = number(9, "rayleigh_mass");
      r.rayleigh_stiffness = number(10, "rayleigh_stiffness");
    }
    const auto outcome = parse_outcome(f[10 + extra], t.header.rule);
    if (!outcome)
      fail("bad outcome '" + printable(f[10 + extra]) + "' for rule " + to_string(t.header.rule));
    r.outcome = *outcome;
    r.iterations = static_cast<int>(integer(11 + extra, "iterations", 0, kInt));
    r.max_displacement = number(12 + extra, "max_displacement");
    r.unstabilisable =
        integer(14 + extra, "unstabilisable", 0, std::numeric_limits<long long>::max());
    if (t.header.rule == StopRule::settled) {
      r.first_entry = static_cast<int>(integer(17 + extra, "first_entry", -kInt, kInt));
      r.left_at = static_cast<int>(integer(18 + extra, "left_at", -kInt, kInt));
      r.settled_at = static_cast<int>(integer(19 + extra, "settled_at", -kInt, kInt));
    } else if (r.outcome == Outcome::restored) {
      r.first_entry = r.iterations;
    }
    t.rows.push_back(r);
    if (keep_lines) t.lines.push_back(line);
  }
  if (!magic || !columns) throw InputError(path + ": not a complete dampbound sweep CSV");
  return t;
}

void merge_sweep_parts(const std::vector<std::string>& parts, const std::string& out) {
  if (parts.empty()) throw InputError("merge: no parts given");
  check_writable(out);
  std::vector<SweepTable> tables;
  for (const std::string& p : parts) {
    tables.push_back(read_sweep_csv(p, true));
    check_sweep_rows(tables.back(), p);  // rows, not only headers
  }
  const SweepHeader& first = tables.front().header;
  // Nothing is allocated by the headers' counts (a forged part may claim 2^31 shards).
  std::map<int, size_t> part_of;
  for (size_t k = 0; k < tables.size(); ++k) {
    const SweepHeader& h = tables[k].header;
    if (h.sweep_id != first.sweep_id)
      throw InputError(parts[k] + ": belongs to sweep " + h.sweep_id + ", not " + first.sweep_id +
                       " (" + parts[0] + ")");
    if (h.shards != first.shards || h.trials != first.trials)
      throw InputError(parts[k] + ": is part of a split into " + std::to_string(h.shards) +
                       ", not " + std::to_string(first.shards));
    const auto [it, fresh] = part_of.emplace(h.shard, k);
    if (!fresh)
      throw InputError(parts[k] + ": part " + std::to_string(h.shard) + "/" +
                       std::to_string(h.shards) + " is also given as " + parts[it->second]);
  }
  for (int s = 1; s <= first.shards; ++s)
    if (!part_of.count(s))
      throw InputError("merge: part " + std::to_string(s) + "/" + std::to_string(first.shards) +
                       " of sweep " + first.sweep_id + " is missing");
  std::uint64_t rows = 0;
  for (const SweepTable& t : tables) rows += t.rows.size();
  if (rows != first.trials)
    throw InputError("merge: the parts hold " + std::to_string(rows) + " rows, and the sweep has " +
                     std::to_string(first.trials) + " trials");
  std::vector<const std::string*> by_trial(static_cast<size_t>(first.trials), nullptr);
  for (size_t k = 0; k < tables.size(); ++k)
    for (size_t r = 0; r < tables[k].rows.size(); ++r) {
      const std::uint64_t t = tables[k].rows[r].trial;
      if (t >= first.trials)
        throw InputError(parts[k] + ": trial " + std::to_string(t) + " is outside the sweep");
      if (by_trial[t])
        throw InputError(parts[k] + ": trial " + std::to_string(t) + " appears twice");
      by_trial[t] = &tables[k].lines[r];
    }
  for (std::uint64_t t = 0; t < first.trials; ++t)
    if (!by_trial[t])
      throw InputError("merge: trial " + std::to_string(t) + " is in no part (" +
                       std::to_string(first.trials) + " trials in the sweep)");
  SweepHeader h = first;
  h.shard = h.shards = 1;
  write_durably(out, [&](std::FILE* f) {
    write_sweep_header(f, h);
    for (const std::string* line : by_trial) {
      std::fwrite(line->data(), 1, line->size(), f);
      std::fputc('\n', f);
    }
  });
}

}  // namespace dampbound
