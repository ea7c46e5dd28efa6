#pragma once
// Crash-safe progress of a sweep. Finished classes are appended to a journal (one line per
// class, each with its own checksum) and the file is fsynced every second or so; a kill -9
// or a power loss loses at most the lines since the last sync, and a line cut short is
// recognised and dropped. On --resume the journal is read back, checked against the sweep,
// deduplicated, its damaged tail cut off, and only the missing classes run. The final CSV is
// written to a temporary file, fsynced and renamed into place.
#include <cstdint>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/io/files.hpp"  // write_durably
#include "core/sweep/kernel.hpp"

namespace dampbound {

/// One finished class as the journal keeps it.
struct JournalEntry {
  std::uint32_t cls = 0;
  TrialResult result;
};

/// The journal line of an entry (with checksum and newline), and its inverse; parse returns
/// nullopt for anything malformed or with a wrong checksum (a torn write).
std::string journal_line(const JournalEntry& e);
std::optional<JournalEntry> parse_journal_line(const std::string& line);

/// How long one run of a sweep had worked when it last synced its journal: a run (the first,
/// or a --resume) writes its number, its wall and CPU seconds so far and the classes it has
/// finished with every sync, so that a sweep finished over several runs can report its time
/// in all.
struct JournalTime {
  int run = 1;
  double wall_s = 0, cpu_s = 0;
  std::uint64_t classes = 0;  ///< classes this run had finished by then
};

/// The journal line of a time record ("t RUN WALL CPU CLASSES" and a checksum), and its
/// inverse.
std::string journal_time_line(const JournalTime& t);
std::optional<JournalTime> parse_journal_time_line(const std::string& line);

/// What a journal held.
struct JournalContents {
  std::vector<JournalEntry> entries;  ///< valid entries, duplicates removed (first kept)
  std::uint64_t valid_bytes = 0;      ///< length of the valid prefix (header included)
  std::uint64_t dropped_lines = 0;    ///< damaged or duplicate lines ignored
  int runs = 0;                       ///< runs that recorded their time (the last run's number)
  double wall_s = 0, cpu_s = 0;       ///< their time in all (each run's last record)
  std::uint64_t timed_classes = 0;    ///< classes those runs had finished at their last record
};

/// Reads PATH. Throws InputError when its first line is not `header` (another sweep or
/// another shard). Entries for a class >= `classes` are an error too.
JournalContents read_journal(const std::string& path, const std::string& header,
                             std::uint64_t classes);

class Journal {
 public:
  /// Creates PATH afresh with `header` as its first line, or, with `resume_valid_bytes` > 0,
  /// opens the existing file and cuts it to that many bytes (dropping a damaged tail).
  Journal(std::string path, const std::string& header, std::uint64_t resume_valid_bytes = 0);
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  /// Buffers an entry; nothing reaches the disk before sync().
  void add(const JournalEntry& e);
  /// Buffers a time record of this run.
  void add_time(const JournalTime& t);
  /// Writes the buffered lines and fsyncs the file.
  void sync();
  /// Closes and deletes the file (after the final CSV is in place).
  void remove();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
  std::string buffer_;
};

}  // namespace dampbound
