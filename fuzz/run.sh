#!/usr/bin/env bash
# Run every fuzz target in fuzz/fuzz_targets for a bounded time each.
#
#   fuzz/run.sh [seconds-per-target]
#
# Seconds per target: the argument, else $FUZZ_SECONDS, else 60. When the targets
# would together run longer than $FUZZ_BUDGET seconds (default 900), each gets an
# equal share of the budget instead (at least 10 s), so adding protocols keeps CI
# bounded. Targets are found by file name: a new fuzz_targets/<name>.rs (with its
# [[bin]] entry in fuzz/Cargo.toml, as `cargo fuzz add` writes it) is picked up.
# Exits non-zero if any target finds a failure; the inputs are in fuzz/artifacts/.
set -euo pipefail
cd "$(dirname "$0")"

seconds="${1:-${FUZZ_SECONDS:-60}}"
budget="${FUZZ_BUDGET:-900}"
toolchain="${FUZZ_TOOLCHAIN:-+nightly}"

targets=()
for file in fuzz_targets/*.rs; do
    targets+=("$(basename "$file" .rs)")
done
for target in "${targets[@]}"; do
    if ! grep -q "^name = \"$target\"" Cargo.toml; then
        echo "fuzz/fuzz_targets/$target.rs has no [[bin]] entry in fuzz/Cargo.toml" >&2
        exit 1
    fi
done
count=${#targets[@]}
if (( count == 0 )); then
    echo "no fuzz targets" >&2
    exit 1
fi
if (( seconds * count > budget )); then
    seconds=$(( budget / count ))
    (( seconds < 10 )) && seconds=10
fi
echo "fuzzing ${count} targets for ${seconds} s each"

cargo "$toolchain" fuzz build

failed=()
summary=()
for target in "${targets[@]}"; do
    mkdir -p "corpus/$target"
    log="$(mktemp)"
    echo "--- $target"
    if cargo "$toolchain" fuzz run "$target" -- \
        -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
        >"$log" 2>&1; then
        status=ok
    else
        status=FAILED
        failed+=("$target")
        tail -n 60 "$log"
    fi
    runs="$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -n 1 || true)"
    corpus="$(ls "corpus/$target" | wc -l)"
    summary+=("$(printf '%-28s %-6s %12s execs  %6s corpus files' "$target" "$status" "${runs:-?}" "$corpus")")
    rm -f "$log"
done

echo
printf '%s\n' "${summary[@]}"
if (( ${#failed[@]} > 0 )); then
    echo "fuzz failures in: ${failed[*]} (inputs in fuzz/artifacts/)" >&2
    exit 1
fi
