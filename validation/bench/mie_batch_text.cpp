// The share of text in the batch command line `attenuvis mie`: for 100,000
// input lines "x m_re m_im" at x near 0.1, 1 and 10 (m = 1.33+1e-8i; x_i =
// x0 (1 + 0.01 i / n), written as the shortest text that reads back, so no
// two lines are equal), the CPU time of
//   (a) mie::batch::run from an in-memory istream to an ostream that discards
//       what it is given (the whole command but its start and the kernel's
//       pipes),
//   (b) mie::spheres() alone on the already-parsed arrays, in the chunks of
//       4096 that run() hands it, with the same options (the physics),
// in alternating blocks, median of the repeats; the text share is
// (a - b) / a.  For where the text time goes, also
//   (c) reading: mie::batch::parse_line on each line (copied into one string),
//   (d) writing: mie::batch::csv_row of each computed row,
//   (e) std::to_chars alone of a row's nine numbers (three shortest, six at 17
//       digits, as the rows carry them).
// (c) and (d) take one line at a time; run() also reads and writes a run of
// lines with one index (as here) once.  Times are CPU seconds of the whole
// process (spheres() may run on several threads; their time is counted, the
// time the process waits for a core on a shared machine is not).
//
// With --write-inputs DIR the three input texts are also written to
// DIR/mie_batch_x{0.1,1,10}.txt, for timing the real command from outside:
//   farm-bench -- sh -c 'exec build/apps/attenuvis mie < DIR/mie_batch_x1.txt > /dev/null'
//
// Usage: mie_batch_text [--lines N] [--repeats R] [--write-inputs DIR]
#include <algorithm>
#include <charconv>
#include <complex>
#include <cstdio>
#include <ctime>
#include <exception>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <streambuf>
#include <string>
#include <vector>

#include "attenuvis/io/number_text.hpp"
#include "attenuvis/mie/batch.hpp"
#include "attenuvis/mie/spheres.hpp"
#include "attenuvis/validation/mie_accuracy.hpp"

namespace mie = attenuvis::mie;

namespace {

volatile std::size_t g_sink = 0;

double process_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// An output stream's buffer that counts the bytes and drops them, as
// /dev/null would, so that (a) pays for formatting but not for memory.
class CountingSink : public std::streambuf {
 public:
  std::size_t bytes = 0;

 protected:
  int_type overflow(int_type c) override {
    if (!traits_type::eq_int_type(c, traits_type::eof())) ++bytes;
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char*, std::streamsize n) override {
    bytes += static_cast<std::size_t>(n);
    return n;
  }
};

struct Input {
  std::string text;
  std::vector<double> x;
  std::vector<std::complex<double>> m;
};

Input make_input(double x0, std::size_t lines) {
  Input in;
  const std::complex<double> m(1.33, 1e-8);
  for (std::size_t i = 0; i < lines; ++i) {
    const double x = x0 * (1.0 + 0.01 * double(i) / double(lines));
    in.text += attenuvis::io::shortest(x) + " 1.33 1e-8\n";
    in.x.push_back(x);
    in.m.push_back(m);
  }
  return in;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Share {
  double a = 0, b = 0;  // median seconds of run() and of spheres()
  double read = 0, write = 0;  // median seconds of parse_line and csv_row over all lines
  double to_chars = 0;         // median seconds of std::to_chars of the rows' numbers
  std::size_t out_bytes = 0;
};

Share measure(const Input& input, int repeats) {
  const mie::Options options;
  mie::SpheresOptions spheres_options;
  spheres_options.options = options;
  constexpr std::size_t kChunk = 4096;  // run()'s chunk (mie/src/batch.cpp)
  const std::size_t n = input.x.size();
  std::vector<mie::Efficiencies<double>> q(n);
  std::vector<double> ta, tb, tc, td, te;
  std::size_t sink = 0;
  Share s;
  for (int r = 0; r < repeats; ++r) {
    {
      std::istringstream in(input.text);
      CountingSink sink;
      std::ostream out(&sink);
      std::ostringstream err;
      const double t0 = process_seconds();
      const std::size_t bad = mie::batch::run(in, out, err, options);
      ta.push_back(process_seconds() - t0);
      if (bad != 0 || !err.str().empty()) throw std::runtime_error("bad lines in the benchmark input: " + err.str());
      s.out_bytes = sink.bytes;
    }
    {
      const double t0 = process_seconds();
      for (std::size_t i = 0; i < n; i += kChunk) {
        const std::size_t count = std::min(kChunk, n - i);
        const auto errors = mie::spheres(input.x.data() + i, input.m.data() + i, count, q.data() + i, spheres_options);
        if (!errors.empty()) throw std::runtime_error("spheres() rejected " + errors.front().message);
      }
      tb.push_back(process_seconds() - t0);
    }
    {
      const double t0 = process_seconds();
      std::string line;
      for (std::size_t at = 0; at < input.text.size();) {
        const std::size_t nl = input.text.find('\n', at);
        line.assign(input.text, at, nl - at);
        at = nl + 1;
        sink += mie::batch::parse_line(line).has_value();
      }
      tc.push_back(process_seconds() - t0);
    }
    {
      const double t0 = process_seconds();
      for (std::size_t i = 0; i < n; ++i) sink += mie::batch::csv_row({input.x[i], input.m[i], {}, {}}, q[i]).size();
      td.push_back(process_seconds() - t0);
    }
    {
      const double t0 = process_seconds();
      char buf[32];
      for (std::size_t i = 0; i < n; ++i) {
        for (const double v : {input.x[i], input.m[i].real(), input.m[i].imag()})
          sink += static_cast<std::size_t>(std::to_chars(buf, buf + sizeof buf, v).ptr - buf);
        for (const double v : {q[i].qext, q[i].qsca, q[i].qabs, q[i].qback, q[i].qpr, q[i].g})
          sink += static_cast<std::size_t>(
              std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 17).ptr - buf);
      }
      te.push_back(process_seconds() - t0);
    }
  }
  g_sink = sink;  // the loops above have an effect
  s.a = median(ta);
  s.b = median(tb);
  s.read = median(tc);
  s.write = median(td);
  s.to_chars = median(te);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::size_t lines = 100000;
    int repeats = 7;
    std::string inputs_dir;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--lines" && i + 1 < argc) {
        lines = std::stoul(argv[++i]);
      } else if (a == "--repeats" && i + 1 < argc) {
        repeats = std::max(1, std::stoi(argv[++i]));
      } else if (a == "--write-inputs" && i + 1 < argc) {
        inputs_dir = argv[++i];
      } else {
        std::cerr << "usage: mie_batch_text [--lines N] [--repeats R] [--write-inputs DIR]\n";
        return 2;
      }
    }
    std::cout << "Text share of `attenuvis mie` (" << attenuvis::validation::timing_machine_description()
              << "; here process CPU time over all threads)\n"
              << lines << " lines 'x 1.33 1e-8', median of " << repeats << " alternating repeats; ns per line\n\n";
    std::printf("%-5s %9s %12s %9s %7s %12s %12s %13s %11s\n", "x", "(a) run", "(b) physics", "text", "share",
                "(c) reading", "(d) writing", "(e) to_chars", "out B/line");
    for (const double x0 : {0.1, 1.0, 10.0}) {
      const Input input = make_input(x0, lines);
      if (!inputs_dir.empty()) {
        const std::string path = inputs_dir + "/mie_batch_x" + attenuvis::io::shortest(x0) + ".txt";
        std::ofstream(path, std::ios::binary) << input.text;
      }
      const Share s = measure(input, repeats);
      const double per = 1e9 / double(lines);
      std::printf("%-5g %9.0f %12.0f %9.0f %6.1f%% %12.0f %12.0f %13.0f %11.1f\n", x0, s.a * per, s.b * per,
                  (s.a - s.b) * per, 100.0 * (s.a - s.b) / s.a, s.read * per, s.write * per, s.to_chars * per,
                  double(s.out_bytes) / double(lines));
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "mie_batch_text: " << e.what() << "\n";
    return 1;
  }
}
