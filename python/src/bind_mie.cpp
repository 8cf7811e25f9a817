// attenuvis._attenuvis.mie: the Lorenz-Mie core over NumPy arrays.
//
// The Python layer (attenuvis/mie.py) broadcasts and converts the inputs to
// contiguous float64 / complex128 (a no-op for arrays that already are) and
// names the results; here the arrays are handed to spheres() without a copy,
// with the GIL released.  The work goes in chunks so that Ctrl-C is honoured
// between them (within a chunk's time, well under a second).
#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdint>
#include <vector>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/layered.hpp"
#include "attenuvis/mie/legendre_moments.hpp"
#include "attenuvis/mie/scattering_matrix.hpp"
#include "attenuvis/mie/spheres.hpp"
#include "bindings.hpp"

namespace py = pybind11;

namespace attenuvis::python {
namespace {

// Without forcecast: a complex array passed where real size parameters are
// expected is refused, not silently cast to its real part.
using Reals = py::array_t<double, py::array::c_style>;
using Complexes = py::array_t<std::complex<double>, py::array::c_style>;

// A chunk ends at 32768 spheres or at ~1e6 series terms (a sphere sums about
// x + 4 x^(1/3) + 2 terms, Wiscombe's count): large enough that every thread
// of spheres() gets work (it sorts and splits each call), small enough that
// a chunk ends within a fraction of a second whatever the size parameters
// (Ctrl-C answered within 0.1 s at x = 2e4, extended precision, on the shared
// 2-core development machine; python/tests/test_mie.py).
constexpr std::size_t chunk_size = 1 << 15;
constexpr double chunk_terms = 1e6;

std::size_t chunk_end(const double* x, std::size_t begin, std::size_t count) {
  const std::size_t last = std::min(count, begin + chunk_size);
  double terms = 0;
  std::size_t end = begin;
  while (end < last && (end == begin || terms < chunk_terms)) {
    const double xi = x[end];
    terms += (xi > 0 && xi < 1e7) ? xi + 4.05 * std::cbrt(xi) + 2 : 2;  // bad x: rejected at once
    ++end;
  }
  return end;
}

// The output arrays of efficiencies() and layered_efficiencies().
struct EfficiencyArrays {
  explicit EfficiencyArrays(std::size_t count)
      : qext(count), qsca(count), qabs(count), qback(count), qpr(count), g(count), terms(count) {
    p[0] = qext.mutable_data(), p[1] = qsca.mutable_data(), p[2] = qabs.mutable_data();
    p[3] = qback.mutable_data(), p[4] = qpr.mutable_data(), p[5] = g.mutable_data();
    pterms = terms.mutable_data();
  }
  // Element i from q (no Python object touched: callable without the GIL).
  void set(std::size_t i, const mie::Efficiencies<double>& q) {
    p[0][i] = q.qext, p[1][i] = q.qsca, p[2][i] = q.qabs, p[3][i] = q.qback, p[4][i] = q.qpr, p[5][i] = q.g;
    pterms[i] = static_cast<std::int64_t>(q.terms);
  }
  py::tuple tuple(const py::list& errors) const {
    return py::make_tuple(qext, qsca, qabs, qback, qpr, g, terms, errors);
  }
  Reals qext, qsca, qabs, qback, qpr, g;
  py::array_t<std::int64_t> terms;
  double* p[6];
  std::int64_t* pterms;
};

py::tuple efficiencies(Reals x, py::object m_object, unsigned threads) {
  const std::size_t count = static_cast<std::size_t>(x.size());
  const double* xs = x.data();
  // m: one complex value for all spheres, or one per sphere.
  std::complex<double> m_scalar;
  const std::complex<double>* ms = nullptr;
  Complexes m_array;
  if (py::isinstance<py::array>(m_object)) {
    m_array = m_object.cast<Complexes>();
    if (static_cast<std::size_t>(m_array.size()) != count)
      throw std::invalid_argument("x and m must have the same number of elements");
    ms = m_array.data();
  } else {
    m_scalar = m_object.cast<std::complex<double>>();
  }
  EfficiencyArrays out(count);
  mie::SpheresOptions options;
  options.threads = threads;
  py::list errors;
  std::vector<mie::Efficiencies<double>> buffer(std::min(count, chunk_size));
  for (std::size_t begin = 0, end = 0; begin < count; begin = end) {
    end = chunk_end(xs, begin, count);
    const std::size_t n = end - begin;
    std::vector<mie::SphereError> bad;
    {
      py::gil_scoped_release release;
      bad = ms ? mie::spheres(xs + begin, ms + begin, n, buffer.data(), options)
               : mie::spheres(xs + begin, m_scalar, n, buffer.data(), options);
      for (std::size_t i = 0; i < n; ++i) out.set(begin + i, buffer[i]);
    }
    for (const auto& e : bad) errors.append(py::make_tuple(begin + e.index, e.message));
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }
  return out.tuple(errors);
}

// Layered spheres of `layers` layers each: x and m hold count × layers
// values, particle by particle, core first.  Chunks of ~1e6 series terms
// (outer x times layers) between checks for Ctrl-C, as efficiencies().
py::tuple layered_efficiencies(Reals x, Complexes m, std::size_t layers, unsigned threads) {
  if (layers == 0 || static_cast<std::size_t>(x.size()) % layers != 0 || m.size() != x.size())
    throw std::invalid_argument("x and m must hold the same whole number of particles of `layers` layers");
  const std::size_t count = static_cast<std::size_t>(x.size()) / layers;
  const double* xs = x.data();
  const std::complex<double>* ms = m.data();
  EfficiencyArrays out(count);
  mie::SpheresOptions options;
  options.threads = threads;
  py::list errors;
  std::vector<mie::Efficiencies<double>> buffer;
  std::vector<std::size_t> offsets;
  for (std::size_t begin = 0, end = 0; begin < count; begin = end) {
    double terms = 0;
    for (end = begin; end < count && (end == begin || terms < chunk_terms) && end - begin < chunk_size; ++end) {
      const double xo = xs[end * layers + layers - 1];
      terms += ((xo > 0 && xo < 1e7) ? xo + 4.05 * std::cbrt(xo) + 2 : 2) * static_cast<double>(layers);
    }
    const std::size_t n = end - begin;
    offsets.resize(n + 1);
    for (std::size_t i = 0; i <= n; ++i) offsets[i] = i * layers;
    buffer.resize(n);
    std::vector<mie::SphereError> bad;
    {
      py::gil_scoped_release release;
      bad = mie::layered_spheres(offsets.data(), xs + begin * layers, ms + begin * layers, n, buffer.data(), options);
      for (std::size_t i = 0; i < n; ++i) out.set(begin + i, buffer[i]);
    }
    for (const auto& e : bad) errors.append(py::make_tuple(begin + e.index, e.message));
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }
  return out.tuple(errors);
}

py::tuple amplitudes(double x, std::complex<double> m, Reals angles) {
  mie::Extras extras;
  extras.angles_deg.assign(angles.data(), angles.data() + angles.size());
  mie::Scattering<double> s;
  {
    py::gil_scoped_release release;
    s = mie::scatter(x, m, extras);
  }
  return py::make_tuple(Complexes(s.s1.size(), s.s1.data()), Complexes(s.s2.size(), s.s2.data()));
}

py::tuple coefficients(double x, std::complex<double> m) {
  mie::Extras extras;
  extras.coefficients = true;
  mie::Scattering<double> s;
  {
    py::gil_scoped_release release;
    s = mie::scatter(x, m, extras);
  }
  return py::make_tuple(Complexes(s.a.size(), s.a.data()), Complexes(s.b.size(), s.b.data()));
}

py::dict scattering_matrix(double x, std::complex<double> m, Reals angles) {
  const std::vector<double> angles_deg(angles.data(), angles.data() + angles.size());
  mie::ScatteringMatrix s;
  {
    py::gil_scoped_release release;
    s = mie::scattering_matrix(x, m, angles_deg);
  }
  py::dict out;
  out["s11"] = Reals(s.s11.size(), s.s11.data());
  out["s12"] = Reals(s.s12.size(), s.s12.data());
  out["s33"] = Reals(s.s33.size(), s.s33.data());
  out["s34"] = Reals(s.s34.size(), s.s34.data());
  out["phase"] = Reals(s.phase.size(), s.phase.data());
  return out;
}

std::size_t order_or_all(py::object max_order) {
  return max_order.is_none() ? mie::all_orders : max_order.cast<std::size_t>();
}

Reals legendre_moments(double x, std::complex<double> m, py::object max_order) {
  const std::size_t order = order_or_all(max_order);
  std::vector<double> chi;
  {
    py::gil_scoped_release release;
    chi = mie::phase_function_moments(x, m, order);
  }
  return Reals(chi.size(), chi.data());
}

py::dict expansion(double x, std::complex<double> m, py::object max_order) {
  const std::size_t order = order_or_all(max_order);
  mie::ScatteringMatrixExpansion<double> e;
  {
    py::gil_scoped_release release;
    mie::Extras extras;
    extras.coefficients = true;
    e = mie::scattering_matrix_expansion(mie::scatter(x, m, extras), order);
  }
  py::dict out;
  out["alpha1"] = Reals(e.alpha1.size(), e.alpha1.data());
  out["alpha2"] = Reals(e.alpha2.size(), e.alpha2.data());
  out["alpha3"] = Reals(e.alpha3.size(), e.alpha3.data());
  out["alpha4"] = Reals(e.alpha4.size(), e.alpha4.data());
  out["beta1"] = Reals(e.beta1.size(), e.beta1.data());
  out["beta2"] = Reals(e.beta2.size(), e.beta2.data());
  return out;
}

Reals phase_from_moments(Reals chi, Reals angles) {
  const std::vector<double> c(chi.data(), chi.data() + chi.size());
  const std::vector<double> a(angles.data(), angles.data() + angles.size());
  const std::vector<double> p = mie::phase_function_from_moments(c, a);
  return Reals(p.size(), p.data());
}

}  // namespace

void bind_mie(py::module_ module) {
  module.def("efficiencies", &efficiencies, py::arg("x"), py::arg("m"), py::arg("threads") = 0,
             "spheres() over contiguous float64 x and complex128 m (array of the same size or "
             "scalar); returns (qext, qsca, qabs, qback, qpr, g, terms, [(index, reason), ...]).");
  module.def("layered_efficiencies", &layered_efficiencies, py::arg("x"), py::arg("m"), py::arg("layers"),
             py::arg("threads") = 0,
             "layered_spheres() over contiguous float64 x and complex128 m holding `layers` values per particle, "
             "core first; returns (qext, qsca, qabs, qback, qpr, g, terms, [(index, reason), ...]).");
  module.def("amplitudes", &amplitudes, py::arg("x"), py::arg("m"), py::arg("angles_deg"));
  module.def("coefficients", &coefficients, py::arg("x"), py::arg("m"));
  module.def("scattering_matrix", &scattering_matrix, py::arg("x"), py::arg("m"), py::arg("angles_deg"));
  module.def("legendre_moments", &legendre_moments, py::arg("x"), py::arg("m"), py::arg("max_order") = py::none());
  module.def("scattering_matrix_expansion", &expansion, py::arg("x"), py::arg("m"),
             py::arg("max_order") = py::none());
  module.def("phase_function_from_moments", &phase_from_moments, py::arg("chi"), py::arg("angles_deg"));
  // Benchmark baseline (validation/bench/python_overhead.py): one spheres()
  // call over the whole array, as a C++ program makes it, timed in C++.
  module.def(
      "spheres_seconds",
      [](Reals x, std::complex<double> m, unsigned threads) {
        std::vector<mie::Efficiencies<double>> out(static_cast<std::size_t>(x.size()));
        mie::SpheresOptions options;
        options.threads = threads;
        py::gil_scoped_release release;
        const auto start = std::chrono::steady_clock::now();
        mie::spheres(x.data(), m, out.size(), out.data(), options);
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      },
      py::arg("x"), py::arg("m"), py::arg("threads") = 0,
      "Seconds one C++ spheres() call takes over x (contiguous float64) at one m: the baseline of the "
      "Python overhead benchmark.");
  module.def(
      "lidar",
      [](double x, std::complex<double> m) {
        const auto l = mie::lidar(mie::sphere(x, m));
        return py::make_tuple(l.backscatter_per_sr, l.lidar_ratio_sr, l.linear_depolarisation);
      },
      py::arg("x"), py::arg("m"), "lidar() of one sphere: (Qback/4pi, 4pi Qext/Qback, 0).");
  module.def(
      "sphere",
      [](double x, std::complex<double> m) {
        const auto q = mie::sphere(x, m);
        return py::make_tuple(q.qext, q.qsca, q.qabs, q.qback, q.qpr, q.g, q.terms);
      },
      py::arg("x"), py::arg("m"), "One sphere by sphere() (the single-call API; raises ValueError).");
}

}  // namespace attenuvis::python
