"""Aerosols from Python: Haze and Aerosol build the same typed conditions as the
command line's haze:/aerosol: grammar, and sigma, optics and table take them."""

import math

import numpy as np
import pytest

from attenuvis import weather as w


def test_haze_is_the_grammars_condition():
    h = w.Haze("urban", rh=95, growth="linear", visibility=5000)
    assert h.text == "haze:urban:rh=95:growth=linear:visibility=5000m"
    assert w.parse(h.text).text == h.text
    assert w.sigma(h).value == w.sigma(h.text).value
    # Scaled to a visibility of 5 km at 550 nm: Koschmieder's 3.912 / sigma is 5 km.
    assert -math.log(0.02) / w.sigma(h).value == pytest.approx(5000, rel=1e-9)


def test_aerosol_mixture_sums_its_components():
    # An external mixture: sigma of the mixture is the sum of its components' (to their errors).
    parts = {"waso": 7000.0, "soot": 8300.0, "inso": 0.4}
    whole = w.sigma(w.Aerosol(parts, rh=70))
    each = [w.sigma(w.Aerosol({name: n}, rh=70)) for name, n in parts.items()]
    assert whole.value == pytest.approx(sum(s.value for s in each), rel=1e-12)
    o = w.optics(w.Aerosol(parts, rh=70))
    assert o.extinction.value == pytest.approx(whole.value, rel=1e-12)
    assert 0 < o.albedo[0] < 1


def test_bad_aerosols_raise():
    with pytest.raises(ValueError, match="aerosol type"):
        w.Haze("suburban", rh=50)
    with pytest.raises(ValueError, match=r"\[0, 99\] %"):
        w.Haze("urban", rh=100)
    with pytest.raises(ValueError, match="cm\\^-3"):
        w.Aerosol({"waso": -3}, rh=50)
    with pytest.raises(ValueError, match="aerosol component"):
        w.Aerosol({"wasp": 3}, rh=50)
    with pytest.raises(TypeError, match="not both"):
        w.Haze("urban", rh=50, visibility=1000, mass=30)


def test_table_sweeps_humidity():
    # The sweep and its order are checked, not the digits: 1e-3 spares the sea salt's
    # resonances at 550 nm the work that 1e-9 asks (seconds per humidity).
    t = w.table("haze:maritime-clean:rh=0..99/33", [550e-9], ["sigma", "albedo"], rel_tolerance=1e-3)
    sigmas = t.value[:, 0]
    assert len(sigmas) == 4
    assert np.all(np.diff(sigmas) > 0)  # sea salt and waso swell with humidity
