#!/bin/sh
# The installed documentation, as a user meets it after `bash scripts/main.sh`:
# the HTML under PREFIX/share/doc/attenuvis/html, named by the installed
# program's --help, and `man attenuvis` from the installed man page.
# Usage: check_installed.sh PREFIX
set -eu
prefix=$1
fail() { echo "FAIL: $*"; exit 1; }
html=$prefix/share/doc/attenuvis/html
[ -f "$html/index.html" ] || fail "$html/index.html is not installed (scripts/setup.sh installs it)"
for page in getting-started guide/mie guide/conditions guide/tables guide/visibility-graphs reference/python \
            reference/cli reference/cpp/mie; do
  [ -f "$html/$page.html" ] || fail "$html/$page.html is not installed"
done
help=$("$prefix/bin/attenuvis" --help) || fail "$prefix/bin/attenuvis --help failed"
case "$help" in *"Documentation: file://$html/index.html"*) ;; *) fail "attenuvis --help does not name $html/index.html" ;; esac
case "$("$prefix/bin/attenuvis" vg --help)" in *"Guide: file://$html/guide/visibility-graphs.html"*) ;;
  *) fail "attenuvis vg --help does not name its guide page in $html" ;; esac
# man(1) finds the page on its own for /usr/local (man-db maps /usr/local/bin
# to /usr/local/share/man); for another prefix it is given the directory.
if [ "$prefix" = /usr/local ]; then manpath_option=""; else manpath_option="-M $prefix/share/man"; fi
# shellcheck disable=SC2086
page=$(MANWIDTH=80 MANPAGER=cat man $manpath_option attenuvis 2>&1) || fail "man attenuvis: $page"
case "$page" in *"attenuvis vg"*) ;; *) fail "man attenuvis does not document attenuvis vg" ;; esac
echo "ok: the documentation is installed in $html and as attenuvis(1)"
