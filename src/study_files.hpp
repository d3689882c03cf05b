// The study's files are written whole or the run fails: every file the study and the merge write
// is closed through close_written, which throws, naming the file and the system's reason
// (ENOSPC on a full device), when a write or the close failed; a file written by a stage that
// keeps its stream to itself is checked afterwards by its line count.
#pragma once

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace certcyl::cli::detail {

// Flushes and closes `f` (written to `p`); throws std::runtime_error if any write or the close failed.
inline void close_written(std::ofstream& f, const std::filesystem::path& p) {
  errno = 0;
  f.close();
  if (!f) throw std::runtime_error("error writing " + p.string() + (errno ? std::string(": ") + std::strerror(errno) : std::string()));
}

// Writes `text` to `p` (replacing it); throws as close_written.
inline void write_whole(const std::filesystem::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::binary);
  if (!f) throw std::runtime_error("error writing " + p.string() + ": " + std::strerror(errno));
  f << text;
  close_written(f, p);
}

// Throws std::runtime_error unless `p` holds exactly `lines` complete lines: a file whose writer
// did not report its errors, checked after it was closed.
inline void check_lines(const std::filesystem::path& p, std::size_t lines) {
  std::ifstream in(p, std::ios::binary);
  std::size_t n = 0;
  char last = '\n';
  for (char buf[1 << 16]; in.read(buf, sizeof buf) || in.gcount() > 0;)
    for (std::streamsize i = 0; i < in.gcount(); ++i) n += (last = buf[i]) == '\n';
  if (!in.eof() || n != lines || last != '\n')
    throw std::runtime_error("error writing " + p.string() + ": " + std::to_string(n) + " complete lines on disk, " + std::to_string(lines) +
                             " written");
}

}  // namespace certcyl::cli::detail
