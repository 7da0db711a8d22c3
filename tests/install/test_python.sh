#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# The Python package as installed: meson install into a temporary prefix,
# move it, then Debian's /usr/bin/python3 imports 'signorini' from there
# (which loads the moved libsignorini.so.0), runs python/tests with pytest
# and the example python/examples/compare.py.
# usage: test_python.sh BUILDDIR SOURCEDIR SANITIZE
# A sanitized library cannot be loaded into an uninstrumented python
# without preloading the runtime: skipped (77) then.
set -eu
build=$1 src=$2 sanitize=$3
[ "$sanitize" = none ] || { echo "test_python: skipped under -Db_sanitize=$sanitize"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
unset SIGNORINI_DATA SIGNORINI_SCENES SIGNORINI_SHADERS SIGNORINI_LIB
fail() { echo "test_python: $*" >&2; exit 1; }
${MESON:-meson} install -C "$build" --no-rebuild --quiet --destdir "$tmp/stage" >"$tmp/install.log" 2>&1 ||
    { cat "$tmp/install.log" >&2; fail "meson install failed"; }
exe=$(find "$tmp/stage" -path '*/bin/signorini' -type f)
prefix=$(dirname "$(dirname "$exe")")
mv "$prefix" "$tmp/moved"
init=$(find "$tmp/moved" -path '*/signorini/__init__.py')
[ -n "$init" ] || fail "no signorini/__init__.py installed"
site=$(dirname "$(dirname "$init")")
cd "$tmp"
PYTHONPATH=$site /usr/bin/python3 -c 'import signorini, sys; print(signorini.__file__, signorini.lib_path)' >where.txt ||
    fail "import signorini failed"
cat where.txt
grep -q "^$tmp/moved/.* $tmp/moved/" where.txt || fail "the package or its library is not the moved prefix's"
PYTHONPATH=$site /usr/bin/python3 -m pytest -q -p no:cacheprovider "$src/python/tests" || fail "pytest failed"
PYTHONPATH=$site /usr/bin/python3 "$src/python/examples/compare.py" compare.png >compare.txt || fail "compare.py failed"
cat compare.txt
[ "$(wc -l <compare.txt)" -eq 3 ] || fail "compare.py: expected three lines"
grep -q '^ssn-tresca *converged' compare.txt || fail "compare.py: ssn-tresca did not converge"
[ "$(head -c 4 compare.png | od -An -c | tr -d ' ')" = '211PNG' ] || fail "compare.png is not a PNG"
echo "test_python: ok"
