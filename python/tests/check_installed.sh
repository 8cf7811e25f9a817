#!/bin/sh
# The installed copy, as a user meets it: from a fresh directory outside the
# checkout, with no ATTENUVIS_DATA_DIR, `attenuvis` from PATH and
# `import attenuvis` from the interpreter's own path, each finding the
# refractive-index tables installed beside it.
# Usage: check_installed.sh PYTHON PREFIX SITE_DIR VERSION
set -eu
python=$1 prefix=$2 site=$3 version=$4
unset ATTENUVIS_DATA_DIR PYTHONPATH || true
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cd "$dir"
PATH="$prefix/bin:$PATH"
# Only a prefix the interpreter does not read by itself (not /usr/local) needs PYTHONPATH.
if ! "$python" -c "import sys; sys.exit(0 if '$site' in sys.path else 1)"; then
  echo "note: $site is not on $python's default path; using PYTHONPATH for this check"
  export PYTHONPATH="$site"
fi
fail() { echo "FAIL: $*"; exit 1; }
command -v attenuvis >/dev/null || fail "attenuvis is not on PATH (not installed in $prefix? scripts/setup.sh installs it)"
got=$(attenuvis --version) || fail "attenuvis --version failed"
case "$got" in *"$version"*) ;; *) fail "attenuvis --version says '$got', expected $version" ;; esac
[ "$(command -v attenuvis)" = "$prefix/bin/attenuvis" ] || fail "attenuvis on PATH is $(command -v attenuvis), not $prefix/bin/attenuvis"
# The program reads its tables from the installed share/attenuvis (not the
# source tree), and a Mie fog, which needs the water table, works.
data=$(attenuvis --version | sed -n 's/^data: *//p')
[ "$data" = "$prefix/share/attenuvis" ] || fail "installed attenuvis reads its tables from '$data', not $prefix/share/attenuvis"
attenuvis sigma fog:advection --wavelength 1550nm >/dev/null || fail "installed attenuvis cannot compute fog:advection"
"$python" - "$site" "$version" <<'PY' || fail "installed Python package"
import os, sys
site, version = sys.argv[1], sys.argv[2]
import attenuvis
assert attenuvis.__version__ == version, (attenuvis.__version__, version)
where = os.path.realpath(attenuvis.__file__)
assert where.startswith(os.path.realpath(site)), f"imported {where}, not the copy in {site}"
data = attenuvis._attenuvis.weather.data_directory()
prefix = os.path.realpath(os.path.join(site, "..", "..", ".."))
assert os.path.realpath(data) == os.path.join(prefix, "share", "attenuvis"), f"tables read from {data}, not the installed copy"
s = attenuvis.weather.sigma("fog:advection", 1550e-9)
assert s.value > 0, s
print("attenuvis", attenuvis.__version__, "from", os.path.dirname(where), "data", data)
PY
echo "ok: attenuvis $version installed in $prefix"
