#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Install into a temporary prefix, MOVE the prefix, and use it as a new user
# would from another directory: the program lists, solves and renders with
# the moved data (found beside the program or library, not in the source
# tree), a program alone says it found no scenes, SIGNORINI_DATA points it
# at data, a removed shaders/ falls back to the compiled-in shaders, and
# examples/client.c builds against the installed signorini.pc and solves.
# usage: test_install.sh BUILDDIR SOURCEDIR HAVE_RENDER SANITIZE CC...
# (SANITIZE: meson's b_sanitize, e.g. "address,undefined" or "none": a
# client of an instrumented library is built with the same flags)
set -eu
build=$1 src=$2 render=$3 sanitize=$4
shift 4
cc=${*:-cc}
san=
[ "$sanitize" = none ] || san="-fsanitize=$sanitize"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
unset SIGNORINI_DATA SIGNORINI_SCENES SIGNORINI_SHADERS
fail() { echo "test_install: $*" >&2; exit 1; }

${MESON:-meson} install -C "$build" --no-rebuild --quiet --destdir "$tmp/stage" >"$tmp/install.log" 2>&1 ||
    { cat "$tmp/install.log" >&2; fail "meson install failed"; }
exe=$(find "$tmp/stage" -path '*/bin/signorini' -type f)
[ -n "$exe" ] || fail "no bin/signorini installed"
prefix=$(dirname "$(dirname "$exe")")
mv "$prefix" "$tmp/moved"
p=$tmp/moved
mkdir "$tmp/elsewhere"
cd "$tmp/elsewhere"

# the installed files
lib=$(find "$p" -name 'libsignorini.so.*.*.*' -type f)
[ -n "$lib" ] || fail "no versioned libsignorini.so"
soname=$(objdump -p "$lib" | awk '/SONAME/ {print $2}')
[ "$soname" = libsignorini.so.0 ] || fail "soname '$soname', expected libsignorini.so.0"
[ -f "$p/include/signorini/signorini.h" ] || fail "no include/signorini/signorini.h"
if find "$p/include" -name '*_impl.h' | grep -q .; then fail "an *_impl.h is installed"; fi
for f in man/man1/signorini.1 man/man1/signorini-solve.1 bash-completion/completions/signorini \
         zsh/site-functions/_signorini; do
    [ -f "$p/share/$f" ] || fail "no share/$f"
done
pc=$(find "$p" -name signorini.pc)
[ -n "$pc" ] || fail "no signorini.pc"

# list, solve, render from another directory with the moved prefix
"$p/bin/signorini" list >list.txt || fail "list failed"
grep -q '^  hertz ' list.txt || fail "list has no hertz"
"$p/bin/signorini" solve hertz >solve.txt || fail "solve hertz failed"
grep -q 'converged' solve.txt || { cat solve.txt >&2; fail "solve hertz did not converge"; }
if grep -q "$src" solve.txt; then fail "solve hertz names the source tree"; fi
# a Gmsh scene: the helper found in the moved prefix's libexec (or a build
# without Gmsh says so)
if "$p/bin/signorini" solve sphere --level 1 >sphere.txt 2>sphere.err; then
    grep -q 'converged' sphere.txt || fail "solve sphere did not converge"
else
    grep -q 'has no Gmsh' sphere.err || { cat sphere.err >&2; fail "solve sphere failed"; }
fi
# a scene only in the moved prefix: the program reads the moved share/
cp "$p/share/signorini/scenes/hertz.ini" "$p/share/signorini/scenes/onlymoved.ini"
"$p/bin/signorini" solve onlymoved >/dev/null || fail "solve of a scene only in the moved prefix failed"
rm "$p/share/signorini/scenes/onlymoved.ini"
if [ "$render" = 1 ]; then
    "$p/bin/signorini" render hertz --png hertz.png >/dev/null || fail "render hertz failed"
    [ "$(head -c 4 hertz.png | od -An -c | tr -d ' ')" = '211PNG' ] || fail "hertz.png is not a PNG"
    # without the shader files: the compiled-in copies
    mv "$p/share/signorini/shaders" "$tmp/shaders.away"
    "$p/bin/signorini" render hertz --png builtin.png >/dev/null || fail "render with the built-in shaders failed"
    cmp -s hertz.png builtin.png || fail "the built-in shaders draw another image"
    mv "$tmp/shaders.away" "$p/share/signorini/shaders"
fi

# the completion's scene list is the moved prefix's
"$p/bin/signorini" help-completion scenes | grep -qx hertz || fail "help-completion scenes: no hertz"

# the program alone (no share/ beside it): an error, not an empty list
mkdir -p "$tmp/lonely/bin"
cp "$p/bin/signorini" "$tmp/lonely/bin/"
if "$tmp/lonely/bin/signorini" list >lonely.txt 2>lonely.err; then fail "list without scenes exited 0"; fi
grep -q 'no scenes found' lonely.err || { cat lonely.err >&2; fail "list without scenes: no message"; }
SIGNORINI_DATA=$p/share/signorini "$tmp/lonely/bin/signorini" list >data.txt || fail "list with SIGNORINI_DATA failed"
grep -q '^  hertz ' data.txt || fail "SIGNORINI_DATA: no hertz"
SIGNORINI_SCENES=$p/share/signorini/scenes "$tmp/lonely/bin/signorini" solve hertz >/dev/null ||
    fail "SIGNORINI_SCENES: solve hertz failed"

# a C client against the installed library, found through pkg-config
export PKG_CONFIG_PATH="$(dirname "$pc")"
libdir=$(pkg-config --variable=libdir signorini)
# shellcheck disable=SC2046
$cc -std=c11 -Wall -Wextra -Werror $san -o client "$src/examples/client.c" \
    $(pkg-config --cflags --libs signorini) -Wl,-rpath,"$libdir" || fail "examples/client.c does not build"
./client hertz ssn-tresca >client.txt || { cat client.txt >&2; fail "client failed"; }
cat client.txt
grep -q '^kkt [0-9.e+-]* iterations [1-9][0-9]* reason converged' client.txt || fail "client output"
kkt=$(awk '/^kkt/ {print $2}' client.txt)
awk -v k="$kkt" 'BEGIN { exit !(k <= 1e-10) }' || fail "client kkt $kkt above 1e-10"
# the library it ran is the moved one
ldd ./client | grep -q "$p" || fail "client does not load the moved libsignorini"

# a problem from plain arrays (examples/arrays.c): no scene, no data files
for h in solve/problem.h scene/problem_file.h out/export.h; do
    [ -f "$p/include/signorini/$h" ] || fail "no include/signorini/$h"
done
# shellcheck disable=SC2046
$cc -std=c11 -Wall -Wextra -Werror $san -o arrays "$src/examples/arrays.c" \
    $(pkg-config --cflags --libs signorini) -Wl,-rpath,"$libdir" || fail "examples/arrays.c does not build"
./arrays >arrays.txt || { cat arrays.txt >&2; fail "arrays failed"; }
cat arrays.txt
grep -q '^kkt [0-9.e+-]* iterations [1-9][0-9]* reason converged' arrays.txt || fail "arrays output"
grep -q '^contact [1-9][0-9]* stick [1-9][0-9]* slip [1-9][0-9]*' arrays.txt || fail "arrays: expected points that stick and points that slip"

# the discrete problem out and back in with the installed program
"$p/bin/signorini" export hertz --format mm hertz.mm >/dev/null || fail "export --format mm failed"
[ -f hertz.mm/problem.json ] && [ -f hertz.mm/K.mtx ] || fail "export: no problem.json or K.mtx"
"$p/bin/signorini" solve --problem hertz.mm --quiet >problem.txt || { cat problem.txt >&2; fail "solve --problem failed"; }
grep -q '^converged' problem.txt || fail "solve --problem did not converge"
if "$p/bin/signorini" export hertz --friction coulomb --format fclib hertz.hdf5 >/dev/null 2>fclib.err; then
    "$p/bin/signorini" solve --problem hertz.hdf5 --quiet >fclib.txt || { cat fclib.txt >&2; fail "solve --problem FCLIB failed"; }
    grep -q '^converged' fclib.txt || fail "solve --problem FCLIB did not converge"
else
    grep -q 'without FCLIB' fclib.err || { cat fclib.err >&2; fail "export --format fclib failed"; }
fi
echo "test_install: ok ($p)"
