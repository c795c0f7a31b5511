#!/usr/bin/env bash
# Fuzzes every parser of petroscope with libFuzzer (clang from Debian: clang, libclang-rt-dev, libomp-dev),
# each for SECONDS or RUNS executions, whichever ends first, with AddressSanitizer and UBSan. Seeds are the
# repository's own files; inputs that crash are written to fuzz/crashes/TARGET/; copy them to
# fuzz/regressions/TARGET/ once fixed, where tests/io/test_fuzz_regressions.cpp replays them on every test run.
#
#     fuzz/run.sh [SECONDS] [RUNS]        # default: 600 s or 1000000 executions per target
set -euo pipefail
seconds=${1:-600}
runs=${2:-1000000}
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build-fuzz
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DPETROSCOPE_FUZZ=ON \
      -DPETROSCOPE_BUILD_TESTS=OFF -DPETROSCOPE_BUILD_BENCHMARKS=OFF > /dev/null
targets=(mineral thin_section interface_case scene values jpeg_header serve_query image_file)
cmake --build "$build" -j"$(nproc)" --target "${targets[@]/#/fuzz_}"

seed() {  # seed TARGET: the corpus folder, filled with the repository's files of that kind
    local corpus=$build/corpus/$1
    mkdir -p "$corpus"
    case $1 in
        mineral) cp "$root"/minerals/*.txt "$corpus"/ ;;
        thin_section) cp "$root"/thin_sections/*/section.txt "$corpus"/ 2>/dev/null || true
                      printf 'name: tiny\ngrain_map: grains.png\nsize_px: 4 4\npixel_size_um: 8\nthickness_um: 30\ngrain 1: quartz, euler 0 90 0\ngrain 2: calcite, cut optic-axis\ngrain 3: albite, euler 10 20 30, thickness 25um\n' > "$corpus"/tiny.txt ;;
        interface_case) cp "$root"/verification/cases/*.json "$corpus"/ ;;
        scene) cp "$root"/scenes/*.json "$corpus"/ ;;
        values) printf '\x0030um' > "$corpus"/length; printf '\x01589nm' > "$corpus"/wavelength
                printf '\x02thickness=10um:60um:10um' > "$corpus"/sweep; printf '\x032/8' > "$corpus"/shard; printf '\x041.5e-3' > "$corpus"/number ;;
        jpeg_header) cp "$root"/fuzz/regressions/jpeg_header/*.jpg "$corpus"/ ;;
        serve_query) cp "$root"/fuzz/regressions/serve_query/* "$corpus"/ ;;
        image_file) cp "$root"/fuzz/regressions/image_file/* "$root"/fuzz/regressions/jpeg_header/*.jpg "$corpus"/ ;;
    esac
    echo "$corpus"
}

for target in "${targets[@]}"; do
    mkdir -p "$root/fuzz/crashes/$target"
    corpus=$(seed "$target")
    echo "== fuzz_$target: up to $seconds s or $runs runs"
    "$build/fuzz/fuzz_$target" "$corpus" -max_total_time="$seconds" -runs="$runs" -timeout=10 -rss_limit_mb=4096 \
        -artifact_prefix="$root/fuzz/crashes/$target/" -print_final_stats=1 2>&1 | grep -E "^stat::number_of_executed_units|^stat::peak_rss|ERROR|SUMMARY|Done" || true
done
