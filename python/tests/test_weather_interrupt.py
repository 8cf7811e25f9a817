"""Ctrl-C stops the long weather calls (sigma, optics, table): a child
process sends itself SIGINT while one runs, KeyboardInterrupt must arrive
within a second, and the same call repeated in that process must give the
value a fresh process gives (nothing partial is kept)."""

import json
import subprocess
import sys
import textwrap

import pytest

# Each workload is a loop of calls that are not memoised between them (a new
# wavelength each time), each one seconds long on two cores, so that the
# signal lands inside C++ work on a faster machine too.  `again(lam)` is the
# same function called after the interruption, at the interrupted wavelength
# (the table: at 20 times it, where the same fog takes a fraction of a second).
WORKLOADS = {
    # Rain drops in the near infrared: the contour up to x ~ 2.4e4, 0.4 s a call.
    "sigma": ("lambda lam: w.sigma('rain:8:mie', lam).value",
              "lambda lam: w.sigma('rain:8:mie', lam).value",
              [1550e-9 + i * 1e-9 for i in range(40)]),
    # Bulk optics of advection fog with its phase function: about 40 s a cell.
    "table": ("lambda lam: w.table(['fog:advection'], [lam], ['phase'])",
              "lambda lam: w.table(['fog:advection', 'rain:8'], [20 * lam], ['phase']).quantities['phase']"
              "[0, 0, ::30].tolist() + w.table(['fog:advection', 'rain:8'], [20 * lam]).value.ravel().tolist()",
              [550e-9 + i * 1e-9 for i in range(10)]),
    "optics": ("lambda lam: w.optics('fog:advection', lam).scattering.value",
               "lambda lam: w.optics('fog:advection', lam).scattering.value",
               [550e-9 + i * 1e-9 for i in range(40)]),
}

CHILD = textwrap.dedent("""
    import json, os, signal, sys, threading, time
    from attenuvis import weather as w
    call = {call}
    again = {again}
    wavelengths = {wavelengths!r}
    sent = []
    def interrupt():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)
    threading.Timer(0.3, interrupt).start()
    current = None
    try:
        for lam in wavelengths:
            current = lam
            call(lam)
        print(json.dumps({{"finished": True}}))
        sys.exit(2)
    except KeyboardInterrupt:
        delay = time.monotonic() - sent[0]
    print(json.dumps({{"delay": delay, "wavelength": current, "again": again(current)}}))
""")

FRESH = textwrap.dedent("""
    import json
    from attenuvis import weather as w
    print(json.dumps(({again})({wavelength!r})))
""")


@pytest.mark.parametrize("kind", sorted(WORKLOADS))
def test_ctrl_c_interrupts_a_weather_call(kind):
    call, again, wavelengths = WORKLOADS[kind]
    run = subprocess.run([sys.executable, "-c", CHILD.format(call=call, again=again, wavelengths=wavelengths)],
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    out = json.loads(run.stdout.strip().splitlines()[-1])
    assert out["delay"] < 1.0, out
    fresh = subprocess.run([sys.executable, "-c", FRESH.format(again=again, wavelength=out["wavelength"])],
                           capture_output=True, text=True, timeout=300)
    assert fresh.returncode == 0, fresh.stdout + fresh.stderr
    # Same bits: JSON writes floats with their shortest round-trip repr.
    assert out["again"] == json.loads(fresh.stdout.strip().splitlines()[-1])
