#include "attenuvis/io/input_file.hpp"

#include "attenuvis/io/number_text.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include <sys/stat.h>

namespace attenuvis::io {
namespace {

// Three digits, so that a file just over the limit does not read as the limit itself.
std::string megabytes(std::size_t bytes) { return significant(static_cast<double>(bytes) / (1024 * 1024), 3) + " MiB"; }

std::size_t checked_size(const std::string& path, std::size_t max_bytes) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw std::runtime_error("'" + path + "': " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw std::runtime_error("'" + path + "' is not a regular file");
  const auto size = static_cast<std::size_t>(st.st_size);
  if (size > max_bytes)
    throw std::runtime_error("'" + path + "' is " + megabytes(size) + ", more than the " + megabytes(max_bytes) +
                             " this reader accepts");
  return size;
}

}  // namespace

void require_readable_input(const std::string& path, std::size_t max_bytes) { checked_size(path, max_bytes); }

std::string read_input_file(const std::string& path, std::size_t max_bytes) {
  const std::size_t size = checked_size(path, max_bytes);
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw std::runtime_error("'" + path + "': " + std::strerror(errno));
  std::string text(size, '\0');
  const std::size_t got = std::fread(text.data(), 1, size, f);
  std::fclose(f);
  // A file that shrank while being read is read as it now is; one that grew is cut at its checked size.
  text.resize(got);
  return text;
}

}  // namespace attenuvis::io
