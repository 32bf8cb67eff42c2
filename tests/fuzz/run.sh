#!/usr/bin/env bash
# make fuzz: builds both libFuzzer targets with ASan + UBSan and runs each
# for FUZZ_SECONDS (default 60) from the seed corpus in tests/fuzz/corpus.
# Installs clang and its fuzzer runtime when missing (Debian; as root).
set -euo pipefail
cd "$(dirname "$0")/../.."
if ! printf 'int LLVMFuzzerTestOneInput(const char*d,unsigned long n){return 0;}' |
        clang -x c -fsanitize=fuzzer - -o /tmp/meshfix_fuzz_probe 2>/dev/null; then
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq && apt-get install -y -qq clang libclang-rt-14-dev >/dev/null
fi
seconds=${FUZZ_SECONDS:-60}
mkdir -p build/fuzz
for target in meshfix loaders; do
    clang -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
        -o build/fuzz/fuzz_$target tests/fuzz/fuzz_$target.c -lm
    mkdir -p build/fuzz/corpus_$target
    echo "== fuzz_$target for $seconds s"
    build/fuzz/fuzz_$target -max_total_time="$seconds" -timeout=10 -print_final_stats=1 -max_len=4096 \
        build/fuzz/corpus_$target tests/fuzz/corpus/$target 2>&1 |
        grep -E 'stat::number_of_executed_units|stat::peak_rss|ERROR|SUMMARY|Done' || true
    test "${PIPESTATUS[0]}" -eq 0
done
