#include "attenuvis/io/staged_file.hpp"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace attenuvis::io {
namespace {

std::atomic<unsigned> temporary_counter{0};

std::string errno_text() { return std::strerror(errno); }

// Creates a new, empty temporary beside `path`; returns its name.
std::string create_temporary(const std::string& path) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    std::string name = path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(temporary_counter++);
    const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      return name;
    }
    if (errno != EEXIST)
      throw std::runtime_error("cannot write '" + path + "': " + errno_text() + " (does the directory exist?)");
  }
  throw std::runtime_error("cannot write '" + path + "': no free temporary name beside it");
}

}  // namespace

void require_regular_or_absent(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return;  // absent (or unreachable: creating it will say why)
  if (!S_ISREG(st.st_mode))
    throw std::runtime_error("'" + path + "' exists and is not a regular file; refusing to replace it");
}

StagedFile::StagedFile(std::string path) : path_(std::move(path)) {
  if (path_.empty()) throw std::runtime_error("an output path is empty");
  require_regular_or_absent(path_);
  temporary_ = create_temporary(path_);
}

StagedFile::StagedFile(StagedFile&& other) noexcept
    : path_(std::move(other.path_)), temporary_(std::move(other.temporary_)), committed_(other.committed_) {
  other.committed_ = true;  // the moved-from object owns nothing
  other.temporary_.clear();
}

StagedFile::~StagedFile() {
  if (!committed_ && !temporary_.empty()) ::unlink(temporary_.c_str());
}

void StagedFile::write(std::string_view text) {
  std::FILE* f = std::fopen(temporary_.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot write '" + path_ + "': " + errno_text());
  const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  const bool closed = std::fclose(f) == 0;
  if (!written || !closed) throw std::runtime_error("error while writing '" + path_ + "' (disk full?)");
}

void StagedFile::commit() {
  // The destination may have become something else since staging.
  require_regular_or_absent(path_);
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0) {
    const std::string why = errno_text();
    ::unlink(temporary_.c_str());
    committed_ = true;
    throw std::runtime_error("cannot rename the temporary file onto '" + path_ + "': " + why);
  }
  committed_ = true;
}

void write_file_atomically(const std::string& path, std::string_view text) {
  StagedFile file(path);
  file.write(text);
  file.commit();
}

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& fill) {
  std::ostringstream text;
  fill(text);
  if (!text) throw std::runtime_error("error while formatting '" + path + "'");
  write_file_atomically(path, text.str());
}

StagedFile& StagedFiles::add(const std::string& path) {
  for (const auto& f : files_)
    if (f.path() == path) throw std::runtime_error("'" + path + "' is named for two outputs of one run");
  files_.emplace_back(path);
  return files_.back();
}

void StagedFiles::commit_all() {
  for (auto& f : files_) f.commit();
  files_.clear();
}

}  // namespace attenuvis::io
