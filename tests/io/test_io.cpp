// attenuvis::io: staged outputs, number text, shell quoting.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

#include "attenuvis/io/input_file.hpp"
#include "attenuvis/io/number_text.hpp"
#include "attenuvis/io/shell.hpp"
#include "attenuvis/io/staged_file.hpp"

namespace fs = std::filesystem;
using namespace attenuvis::io;

namespace {
fs::path fresh_dir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("attenuvis_io_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
std::string read(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}
std::size_t entries(const fs::path& d) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(d), fs::directory_iterator()));
}
}  // namespace

TEST_CASE("staged file: appears only on commit, temporary removed otherwise", "[io]") {
  const fs::path d = fresh_dir("staged");
  const std::string out = (d / "a.txt").string();
  {
    StagedFile f(out);
    f.write("hello");
    CHECK_FALSE(fs::exists(out));
    CHECK(fs::exists(f.temporary_path()));
  }
  CHECK(entries(d) == 0);  // abandoned: nothing left behind
  write_file_atomically(out, "one");
  write_file_atomically(out, [](std::ostream& o) { o << "two " << 2; });
  CHECK(read(out) == "two 2");
  CHECK(entries(d) == 1);
  fs::remove_all(d);
}

TEST_CASE("staged file: refuses a destination that is not a regular file", "[io]") {
  const fs::path d = fresh_dir("special");
  CHECK_THROWS_WITH(StagedFile((d).string()), Catch::Contains("not a regular file"));
  if (fs::exists("/dev/null")) CHECK_THROWS_WITH(write_file_atomically("/dev/null", "x"), Catch::Contains("/dev/null"));
  CHECK_THROWS_WITH(StagedFile((d / "missing" / "x.txt").string()), Catch::Contains("does the directory exist"));
  CHECK(entries(d) == 0);
  fs::remove_all(d);
}

TEST_CASE("staged files: all or nothing, one path per output", "[io]") {
  const fs::path d = fresh_dir("set");
  const std::string a = (d / "a.csv").string(), b = (d / "b.json").string();
  {
    StagedFiles set;
    set.add(a).write("a");
    CHECK_THROWS_WITH(set.add(a), Catch::Contains("two outputs"));
    set.add(b).write("b");
    // A failure before commit_all leaves neither.
  }
  CHECK(entries(d) == 0);
  StagedFiles set;
  set.add(a).write("a");
  set.add(b).write("b");
  set.commit_all();
  CHECK(read(a) == "a");
  CHECK(read(b) == "b");
  fs::remove_all(d);
}

TEST_CASE("number text: parse the whole string, name the input", "[io]") {
  CHECK(parse_double("1.5", "rate") == 1.5);
  CHECK(parse_double("+2e3", "rate") == 2000.0);
  CHECK(parse_double("-0.25", "rate") == -0.25);
  CHECK_THROWS_WITH(parse_double("1.5x", "rate"), "rate: '1.5x' is not a number");
  CHECK_THROWS_WITH(parse_double("", "rate"), "rate: a number is missing");
  CHECK_THROWS_WITH(parse_double("inf", "rate"), Catch::Contains("'inf'"));
  CHECK_THROWS_WITH(parse_double("nan", "rate"), Catch::Contains("'nan'"));
  CHECK_THROWS_WITH(parse_double("1e999", "rate"), Catch::Contains("out of the range"));
}

TEST_CASE("number text: shortest round trip and significant digits", "[io]") {
  CHECK(shortest(1.7) == "1.7");
  CHECK(shortest(1550.0) == "1550");
  CHECK(shortest(0.1 + 0.2) == "0.30000000000000004");
  for (double v : {1.0 / 3.0, 6.02214076e23, 5e-324, -2.5e-310, 1.7976931348623157e308})
    CHECK(parse_double(shortest(v), "v") == v);
  CHECK(significant(0.028746778511569, 4) == "0.02875");
  CHECK(significant(1234567.0, 3) == "1.23e+06");
}

TEST_CASE("shell quoting survives quotes and spaces", "[io]") {
  CHECK(shell_quote("plain") == "'plain'");
  CHECK(shell_quote("it's a b") == "'it'\\''s a b'");
}

TEST_CASE("input files: regular files only, within the reader's limit", "[io]") {
  const fs::path d = fresh_dir("input");
  const std::string p = (d / "in.txt").string();
  write_file_atomically(p, "0123456789");
  CHECK(read_input_file(p, 100) == "0123456789");
  CHECK_THROWS_WITH(read_input_file(p, 5), Catch::Contains("more than"));
  CHECK_THROWS_WITH(read_input_file(d.string(), 100), Catch::Contains("not a regular file"));
  if (fs::exists("/dev/zero")) CHECK_THROWS_WITH(read_input_file("/dev/zero", 100), Catch::Contains("not a regular file"));
  CHECK_THROWS_WITH(read_input_file((d / "missing").string(), 100), Catch::Contains("No such file"));
  fs::remove_all(d);
}

// ---- Internal invariants (check.hpp) ----------------------------------------

#include <csignal>
#include <sys/wait.h>

#include "attenuvis/io/check.hpp"

TEST_CASE("internal check: the message names the expression, both values, the file and the line", "[io][check]") {
  CHECK(check_failure_text("a.cpp", 12, "n == m", "n = 3, m = 4") ==
        "attenuvis: internal check failed at a.cpp:12: n == m (n = 3, m = 4)");
  CHECK(check_failure_text("a.cpp", 12, "ok", "") == "attenuvis: internal check failed at a.cpp:12: ok");
  CHECK(detail::check_values("x", 0.1, "y", 2) == "x = 0.10000000000000001, y = 2");
}

TEST_CASE("internal check: a failed check aborts where checks are on, and costs nothing where they are off",
          "[io][check]") {
  int fds[2];
  REQUIRE(::pipe(fds) == 0);
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    ::dup2(fds[1], 2);
    const int three = 3, four = 4;
    ATTENUVIS_CHECK_EQ(three, four);
    ::_exit(0);
  }
  ::close(fds[1]);
  std::string err;
  char buffer[256];
  for (ssize_t n; (n = ::read(fds[0], buffer, sizeof buffer)) > 0;) err.append(buffer, static_cast<std::size_t>(n));
  ::close(fds[0]);
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
#if defined(ATTENUVIS_CHECKS)
  REQUIRE(WIFSIGNALED(status));
  CHECK(WTERMSIG(status) == SIGABRT);
  CHECK_THAT(err, Catch::Contains("internal check failed at") && Catch::Contains("three == four (three = 3, four = 4)"));
#else
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  CHECK(err.empty());
#endif
}
