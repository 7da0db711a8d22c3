#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Fuzz the readers for SECONDS each (default 60) with libFuzzer under
# AddressSanitizer + UndefinedBehaviorSanitizer: configures a clang build
# in ./build-fuzz the first time (Debian 12: clang-14 and libclang-rt-14-dev,
# which carries libclang_rt.fuzzer), seeds a working corpus per harness,
# and ends with one line per harness
#   fuzz_NAME: N executions in S s, cov C, ft F, corpus K, no crash
# or exits non-zero with libFuzzer's crash report (the input is saved as
# build-fuzz/crash-*). New corpus entries stay in build-fuzz/corpus-NAME.
# The harnesses: scene (the scene reader; seeds: every scene and scene
# test file) and mm (the MatrixMarket reader; seeds: tests/fuzz/mm).
# usage: run.sh [SECONDS [HARNESS...]]
set -eu
cd "$(dirname "$0")/../.."
secs=${1:-60}
[ $# -gt 0 ] && shift
harnesses=${*:-scene mm}
bd=${FUZZ_BUILDDIR:-build-fuzz}

if [ ! -f "$bd/build.ninja" ]; then
    CC=clang meson setup "$bd" -Dbuildtype=debugoptimized -Db_sanitize=address,undefined \
        -Db_lundef=false -Drender=disabled -Dc_args=-fsanitize=fuzzer-no-link >&2
fi

for h in $harnesses; do
    case $h in
        scene) seeds="scenes/*.ini tests/scene/good/*.ini tests/scene/bad/*.ini"
               opts="-max_len=8192 -dict=tests/fuzz/scene.dict" ;;
        mm)    seeds="tests/fuzz/mm/*.mtx"
               opts="-max_len=4096" ;;
        *)     echo "run.sh: unknown harness '$h' (scene, mm)" >&2; exit 2 ;;
    esac
    ninja -C "$bd" "tests/fuzz/fuzz_$h" >&2
    corpus=$bd/corpus-$h
    mkdir -p "$corpus"
    # shellcheck disable=SC2086
    cp $seeds "$corpus"/
    log=$bd/fuzz-$h.log
    status=0
    # shellcheck disable=SC2086
    UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 ASAN_OPTIONS=detect_leaks=1 \
        "$bd/tests/fuzz/fuzz_$h" -max_total_time="$secs" $opts \
        -artifact_prefix="$bd/" -print_final_stats=1 "$corpus" >"$log" 2>&1 || status=$?
    if [ "$status" -ne 0 ]; then
        tail -n 60 "$log" >&2
        echo "fuzz_$h: crash or contract broken (exit $status), see $log" >&2
        exit 1
    fi
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    last=$(grep -E '^#[0-9]+' "$log" | tail -n 1)
    cov=$(printf '%s\n' "$last" | sed -n 's/.* cov: \([0-9]*\).*/\1/p')
    ft=$(printf '%s\n' "$last" | sed -n 's/.* ft: \([0-9]*\).*/\1/p')
    corp=$(printf '%s\n' "$last" | sed -n 's/.* corp: \([0-9]*\).*/\1/p')
    echo "fuzz_$h: ${runs:-?} executions in $secs s, cov ${cov:-?}, ft ${ft:-?}, corpus ${corp:-?}, no crash"
done
