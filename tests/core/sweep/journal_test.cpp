// The sweep journal (torn lines, duplicates, another sweep's journal), the durable CSV write
// and the merge checks.
#include "core/sweep/journal.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "core/io/format.hpp"
#include "core/sweep/csv.hpp"
#include "core/sweep/grid.hpp"
#include "dampbound/physics/bounds.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {
namespace {

std::string journal_temp_path(const std::string& name) {
  return ::testing::TempDir() + "dampbound_" + std::to_string(::getpid()) + "_" + name;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

JournalEntry entry(std::uint32_t cls, Outcome o, int it, double d) {
  JournalEntry e;
  e.cls = cls;
  e.result.outcome = o;
  e.result.iterations = it;
  e.result.max_displacement = d;
  e.result.violations = 1234567890123;
  e.result.unstabilisable = 7;
  e.result.clamped = 3;
  e.result.zero_length_springs = 0;
  return e;
}

TEST(SweepJournal, LineRoundTripsExactly) {
  const JournalEntry e = entry(42, Outcome::not_restored, 1000, 0.1 + 0.2);
  JournalEntry back;
  std::string line = journal_line(e);
  ASSERT_EQ(line.back(), '\n');
  line.pop_back();
  ASSERT_TRUE(parse_journal_line(line));
  back = *parse_journal_line(line);
  EXPECT_EQ(back.cls, 42u);
  EXPECT_EQ(back.result.outcome, Outcome::not_restored);
  EXPECT_EQ(back.result.max_displacement, 0.1 + 0.2);
  EXPECT_EQ(back.result.violations, 1234567890123);
  JournalEntry inf_e = entry(1, Outcome::diverged, 9, HUGE_VAL);
  line = journal_line(inf_e);
  line.pop_back();
  ASSERT_TRUE(parse_journal_line(line));
  back = *parse_journal_line(line);
  EXPECT_TRUE(std::isinf(back.result.max_displacement));
  // Any torn or altered line fails its checksum.
  for (size_t cut = 1; cut < line.size(); cut += 3)
    EXPECT_FALSE(parse_journal_line(line.substr(0, cut))) << cut;
  std::string altered = line;
  altered[2] = altered[2] == '1' ? '2' : '1';
  EXPECT_FALSE(parse_journal_line(altered));
}

TEST(SweepJournal, SettledRuleLinesKeepTheBandFields) {
  JournalEntry e = entry(8, Outcome::not_settled, 1000, 0.25);
  e.result.first_entry = 12;
  e.result.left_at = 63;
  std::string line = journal_line(e);
  EXPECT_NE(line.find(" b 12 63 0 "), std::string::npos);
  line.pop_back();
  JournalEntry back;
  ASSERT_TRUE(parse_journal_line(line));
  back = *parse_journal_line(line);
  EXPECT_EQ(back.result.outcome, Outcome::not_settled);
  EXPECT_EQ(back.result.first_entry, 12);
  EXPECT_EQ(back.result.left_at, 63);
  EXPECT_EQ(back.result.settled_at, 0);
  e = entry(9, Outcome::settled, 1000, 0.001);
  e.result.first_entry = 230;
  e.result.left_at = 231;
  e.result.settled_at = 260;
  line = journal_line(e);
  line.pop_back();
  ASSERT_TRUE(parse_journal_line(line));
  back = *parse_journal_line(line);
  EXPECT_EQ(back.result.outcome, Outcome::settled);
  EXPECT_EQ(back.result.settled_at, 260);
  // A first-entry restore writes the old line: its first entry is its iteration.
  e = entry(10, Outcome::restored, 112, 0.04);
  e.result.first_entry = 112;
  line = journal_line(e);
  EXPECT_EQ(line.find(" b "), std::string::npos);
  line.pop_back();
  ASSERT_TRUE(parse_journal_line(line));
  back = *parse_journal_line(line);
  EXPECT_EQ(back.result.first_entry, 112);
}

TEST(SweepJournal, ResumeDropsTornTailAndDuplicates) {
  const std::string path = journal_temp_path("journal");
  const std::string header = "dampbound-journal v1 sweep=abc 1/1 classes=10";
  {
    Journal j(path, header);
    j.add(entry(3, Outcome::restored, 34, 0.04));
    j.add(entry(5, Outcome::diverged, 12, HUGE_VAL));
    j.add(entry(3, Outcome::restored, 34, 0.04));  // a duplicate
    j.sync();
  }
  // A kill -9 in the middle of a write: half a line at the end.
  const std::string torn = journal_line(entry(7, Outcome::restored, 50, 0.01));
  {
    std::ofstream out(path, std::ios::app | std::ios::binary);
    out << torn.substr(0, torn.size() / 2);
  }
  JournalContents jc = read_journal(path, header, 10);
  ASSERT_EQ(jc.entries.size(), 2u);
  EXPECT_EQ(jc.entries[0].cls, 3u);
  EXPECT_EQ(jc.entries[1].cls, 5u);
  EXPECT_EQ(jc.dropped_lines, 2u);  // the duplicate and the torn line
  {
    Journal j(path, header, jc.valid_bytes);  // cuts the torn tail off, then appends
    j.add(entry(7, Outcome::restored, 50, 0.01));
    j.sync();
  }
  jc = read_journal(path, header, 10);
  ASSERT_EQ(jc.entries.size(), 3u);
  EXPECT_EQ(jc.entries[2].cls, 7u);
  EXPECT_EQ(jc.dropped_lines, 1u);  // only the duplicate now
  // Another sweep's journal is refused, and so is a class outside the sweep.
  EXPECT_THROW(read_journal(path, "dampbound-journal v1 sweep=xyz 1/1 classes=10", 10), InputError);
  EXPECT_THROW(read_journal(path, header, 6), InputError);
  std::remove(path.c_str());
}

TEST(SweepJournal, TimeRecordsAddUpOverRuns) {
  const std::string path = journal_temp_path("journal_time");
  const std::string header = "dampbound-journal v1 sweep=abc 1/1 classes=10";
  JournalTime t;
  t.run = 2;
  t.wall_s = 12.5;
  t.cpu_s = 24.25;
  t.classes = 17;
  JournalTime back;
  const auto parsed =
      parse_journal_time_line(journal_time_line(t).substr(0, journal_time_line(t).size() - 1));
  ASSERT_TRUE(parsed);
  back = *parsed;
  EXPECT_EQ(back.run, 2);
  EXPECT_EQ(back.wall_s, 12.5);
  EXPECT_EQ(back.cpu_s, 24.25);
  EXPECT_EQ(back.classes, 17u);
  EXPECT_FALSE(parse_journal_line(journal_time_line(t)));  // not a class line
  {
    Journal j(path, header);
    j.add(entry(1, Outcome::restored, 30, 0.04));
    j.add_time({1, 10.0, 19.0, 1});
    j.add(entry(2, Outcome::restored, 31, 0.04));
    j.add_time({1, 20.0, 39.0, 2});  // the first run's last record counts
    j.sync();
  }
  JournalContents jc = read_journal(path, header, 10);
  EXPECT_EQ(jc.entries.size(), 2u);
  EXPECT_EQ(jc.runs, 1);
  EXPECT_DOUBLE_EQ(jc.wall_s, 20.0);
  EXPECT_DOUBLE_EQ(jc.cpu_s, 39.0);
  EXPECT_EQ(jc.timed_classes, 2u);
  {
    Journal j(path, header, jc.valid_bytes);  // a second run
    j.add(entry(3, Outcome::diverged, 3, HUGE_VAL));
    j.add_time({2, 5.0, 9.5, 1});
    j.sync();
  }
  // A torn time record at the end is dropped like a torn class line.
  const std::string torn = journal_time_line({2, 7.0, 13.0, 1});
  {
    std::ofstream out(path, std::ios::app | std::ios::binary);
    out << torn.substr(0, torn.size() - 4);
  }
  jc = read_journal(path, header, 10);
  EXPECT_EQ(jc.entries.size(), 3u);
  EXPECT_EQ(jc.runs, 2);
  EXPECT_DOUBLE_EQ(jc.wall_s, 25.0);
  EXPECT_DOUBLE_EQ(jc.cpu_s, 48.5);
  EXPECT_EQ(jc.timed_classes, 3u);
  EXPECT_EQ(jc.dropped_lines, 1u);
  std::remove(path.c_str());
}

TEST(SweepJournal, DurableWriteReplacesWhole) {
  const std::string path = journal_temp_path("durable.txt");
  write_durably(path, [](std::FILE* f) { std::fputs("one\n", f); });
  EXPECT_EQ(slurp(path), "one\n");
  EXPECT_THROW(write_durably(path, [](std::FILE*) { throw InputError("stop"); }), InputError);
  EXPECT_EQ(slurp(path), "one\n");  // a failed write leaves the old file as it was
  EXPECT_THROW(write_durably("/nonexistent-dir/x.csv", [](std::FILE*) {}), InputError);
  std::remove(path.c_str());
}

/// A two-part sweep CSV written by hand with the real writer.
std::string write_part(const std::string& name, const std::string& id, int shard, int shards,
                       const std::vector<std::uint64_t>& trials, std::uint64_t total) {
  const std::string path = journal_temp_path(name);
  SweepHeader h;
  h.sweep_id = id;
  h.scene_name = "test";
  h.definition = "m=0.001 kappa=0.001:" + format_number(0.001 * static_cast<double>(total)) +
                 ":0.001 gamma=0.002 dt=0.05 policy=fixed factor=1 max-iter=100";
  h.trials = total;
  h.classes = total;
  h.similarity = "on";
  h.shard = shard;
  h.shards = shards;
  write_durably(path, [&](std::FILE* f) {
    write_sweep_header(f, h);
    // A grid the merge's row check accepts: kappa = 0.001 (t + 1), every trial its own class.
    for (std::uint64_t t : trials) {
      const double kappa = parse_decimal(std::to_string(t + 1) + "e-3", "--kappa").value();
      std::fprintf(f, "%llu,0.001,%s,0.002,%.17g,0.05,fixed,1,%llu,1,restored,34,0.04,0,0,0,0\n",
                   static_cast<unsigned long long>(t), format_number(kappa).c_str(),
                   0.002 / lower_bound(0.001, kappa),
                   static_cast<unsigned long long>(t));
    }
  });
  return path;
}

TEST(SweepMerge, JoinsPartsAndRefusesBadSets) {
  const std::string a = write_part("p1.csv", "id1", 1, 2, {0, 2, 4}, 5);
  const std::string b = write_part("p2.csv", "id1", 2, 2, {1, 3}, 5);
  const std::string whole = write_part("whole.csv", "id1", 1, 1, {0, 1, 2, 3, 4}, 5);
  const std::string out = journal_temp_path("merged.csv");
  merge_sweep_parts({b, a}, out);
  EXPECT_EQ(slurp(out), slurp(whole));
  const SweepTable t = read_sweep_csv(out);
  ASSERT_EQ(t.rows.size(), 5u);
  EXPECT_EQ(t.rows[3].trial, 3u);
  EXPECT_EQ(t.rows[3].outcome, Outcome::restored);

  const std::string other = write_part("p2x.csv", "id2", 2, 2, {1, 3}, 5);
  const std::string dup = write_part("p2d.csv", "id1", 2, 2, {1, 2, 3}, 5);
  const std::string gap = write_part("p2g.csv", "id1", 2, 2, {1}, 5);
  EXPECT_THROW(merge_sweep_parts({a, other}, out), InputError);  // another sweep
  EXPECT_THROW(merge_sweep_parts({a}, out), InputError);         // a part missing
  EXPECT_THROW(merge_sweep_parts({a, a}, out), InputError);      // a part twice
  EXPECT_THROW(merge_sweep_parts({a, dup}, out), InputError);    // a trial twice
  EXPECT_THROW(merge_sweep_parts({a, gap}, out), InputError);    // a trial missing
  for (const std::string& p : {a, b, whole, other, dup, gap, out}) std::remove(p.c_str());
}

TEST(SweepJournal, EmptyOrTornHeaderStartsAfresh) {
  // Killed between creating the journal and writing its header: nothing was done, and the
  // journal must neither block --resume nor be taken for another sweep's.
  const std::string path = journal_temp_path("torn_header.journal");
  const std::string header = "dampbound-journal v1 sweep=abc 1/1 classes=10";
  for (const std::string& text : {std::string(), header.substr(0, 17)}) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
    const JournalContents jc = read_journal(path, header, 10);
    EXPECT_EQ(jc.valid_bytes, 0u);
    EXPECT_TRUE(jc.entries.empty());
    Journal j(path, header, jc.valid_bytes);  // replaces it
  }
  EXPECT_EQ(slurp(path), header + "\n");
  std::ofstream(path, std::ios::binary | std::ios::trunc) << "dampbound-journal v1 sweep=abd";
  EXPECT_THROW(read_journal(path, header, 10), InputError);  // another sweep's, torn
  std::remove(path.c_str());
  const std::string dir = journal_temp_path("dir.journal");
  ::mkdir(dir.c_str(), 0700);
  try {
    read_journal(dir, header, 10);
    ADD_FAILURE() << "a directory was read as a journal";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), dir + ": is a directory, not a file");
  }
  ::rmdir(dir.c_str());
}

TEST(SweepJournal, ForgedLinesWithAGoodChecksumAreRefused) {
  // A good checksum is easy to forge: what no run can write must not reach the CSV.
  auto parses = [](const JournalEntry& e) {
    std::string line = journal_line(e);
    line.pop_back();  // the newline
    return parse_journal_line(line).has_value();
  };
  EXPECT_TRUE(parses(entry(1, Outcome::restored, 34, 0.04)));
  EXPECT_TRUE(parses(entry(1, Outcome::diverged, 3, HUGE_VAL)));  // a diverged run may end at inf
  EXPECT_FALSE(parses(entry(1, Outcome::restored, 34, HUGE_VAL)));
  EXPECT_FALSE(parses(entry(1, Outcome::not_restored, 34, -1.0)));
  EXPECT_FALSE(parses(entry(1, Outcome::restored, -34, 0.04)));
  JournalEntry negative = entry(1, Outcome::restored, 34, 0.04);
  negative.result.violations = -5;
  EXPECT_FALSE(parses(negative));
}

TEST(SweepMerge, ForgedHeadersAllocateNothing) {
  // A header claiming 2^64-1 trials or 2^31-1 shards was allocated for before being checked.
  const std::string a = write_part("f1.csv", "id1", 1, 2, {0, 2, 4}, 5);
  const std::string out = journal_temp_path("forged_merged.csv");
  std::string text = slurp(a);
  for (const char* shards : {"# shard: 1/2147483647", "# shard: 1/999999999"}) {
    std::string forged = text;
    forged.replace(forged.find("# shard: 1/2"), 12, shards);
    std::ofstream(a, std::ios::binary | std::ios::trunc) << forged;
    try {
      merge_sweep_parts({a}, out);
      ADD_FAILURE() << "merged one part of " << shards;
    } catch (const InputError& e) {
      const std::string what = e.what();
      // 2^31-1 parts are refused as the header is read; 999999999 for the missing part 2.
      EXPECT_TRUE(what.find("bad shard line") != std::string::npos ||
                  what.find("part 2/999999999 of sweep id1 is missing") != std::string::npos)
          << what;
    }
  }
  std::string forged = text;
  forged.replace(forged.find("# trials: 5"), 11, "# trials: 18446744073709551615");
  std::ofstream(a, std::ios::binary | std::ios::trunc) << forged;
  EXPECT_THROW(read_sweep_csv(a), InputError);
  EXPECT_FALSE(std::ifstream(out).good());
  std::remove(a.c_str());
}

}  // namespace
}  // namespace dampbound
