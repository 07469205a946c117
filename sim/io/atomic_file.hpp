#pragma once
/// Files that appear whole or not at all: content goes to `PATH.tmp` and is
/// renamed over PATH only by commit(). A writer destroyed without commit()
/// (an exception, a crash) removes its temporary file, so readers never see a
/// half-written result. rename() within one directory is atomic on POSIX.

#include <filesystem>
#include <fstream>
#include <string>

namespace tcb {

class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ofstream& stream() { return m_stream; }
  /// Flushes, checks the stream, and renames the temporary file into place.
  /// Throws std::runtime_error when writing failed (disk full, ...).
  void commit();

 private:
  std::filesystem::path m_path;
  std::filesystem::path m_temp_path;
  std::ofstream m_stream;
  bool m_committed = false;
};

/// Writes the whole string to path atomically.
void write_file_atomically(const std::filesystem::path& path, const std::string& content);

/// Reads a whole file; throws InputError (no line) when it cannot be opened
/// or is a directory.
std::string read_file(const std::filesystem::path& path);

}  // namespace tcb
