#include "sim/io/atomic_file.hpp"

#include <sstream>
#include <stdexcept>
#include <system_error>

#include "sim/io/input_error.hpp"

namespace tcb {

AtomicFile::AtomicFile(std::filesystem::path path)
    : m_path(std::move(path)), m_temp_path(m_path.string() + ".tmp") {
  m_stream.open(m_temp_path, std::ios::binary | std::ios::trunc);
  if (!m_stream) throw std::runtime_error("cannot open " + m_temp_path.string() + " for writing");
}

AtomicFile::~AtomicFile() {
  if (!m_committed) {
    m_stream.close();
    std::error_code ignored;
    std::filesystem::remove(m_temp_path, ignored);
  }
}

void AtomicFile::commit() {
  m_stream.flush();
  if (!m_stream) throw std::runtime_error("writing " + m_temp_path.string() + " failed");
  m_stream.close();
  std::filesystem::rename(m_temp_path, m_path);
  m_committed = true;
}

void write_file_atomically(const std::filesystem::path& path, const std::string& content) {
  AtomicFile file(path);
  file.stream() << content;
  file.commit();
}

std::string read_file(const std::filesystem::path& path) {
  // A directory opens as an empty stream on Linux: say what it is instead of
  // letting a parser report a missing section.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path.string(), 0, "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "cannot open file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace tcb
